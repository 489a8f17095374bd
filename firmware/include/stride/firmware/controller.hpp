// Controller: one control cycle of the firmware, step(SensorFrame, Tick) -> CommandFrame.
//
// step() is pure with respect to the outside world: no I/O, no clock, no heap allocation and
// no exceptions; the same step runs on the robot, in the simulator and in every optimiser
// evaluation. Order inside a step: requests -> attitude estimate (attitude_estimator.hpp) ->
// fall detection -> motion manager (active engine) -> torque switch -> safety layer (always
// last).
//
// Thread rules: step() on the control thread. request(), set_torque() and status() may be
// called from one other thread (console); they never block the control thread (it try-locks).
#pragma once

#include <array>
#include <cstdint>
#include <mutex>

#include "stride/firmware/attitude_estimator.hpp"
#include "stride/firmware/motion_manager.hpp"
#include "stride/firmware/motion_request.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/safety_layer.hpp"
#include "stride/firmware/servo_table.hpp"
#include "stride/hal/command_frame.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw {

/// A snapshot of the controller for status displays. Plain data.
struct ControllerStatus {
  hal::Tick tick = 0;
  MotionState state = MotionState::kStand;
  std::array<char, 32> script{};  ///< active script name, NUL-terminated
  bool torque_on = true;
  std::uint32_t refused_requests = 0;
  std::uint32_t dropped_requests = 0;  ///< requests lost because the mailbox was full
  SafetyReport safety{};
  hal::SensorFrame sensors{};  ///< the latest readings
};

/// The optional motion engines a Controller drives (null: that motion is unavailable).
struct ControllerEngines {
  WalkControl* walk = nullptr;
  ScriptControl* script = nullptr;
};

class Controller {
 public:
  using Engines = ControllerEngines;

  /// Registers the controller's parameters. `servos`, `attitude` and the engines must outlive
  /// it. `attitude` is the firmware's one attitude estimate: step() updates it with the tick's
  /// IMU before anything reads it (the engines were built reading the same object).
  Controller(ParameterStore& params, const ServoTable& servos, std::int64_t period_ns,
             AttitudeEstimator& attitude, Engines engines = {});

  /// One control cycle. Real-time: no I/O, no clock, no allocation, no exceptions.
  hal::CommandFrame step(const hal::SensorFrame& sensors, hal::Tick tick) noexcept;

  /// Queues a motion request for the next step (up to 8 in flight; more are dropped and
  /// counted). Any thread.
  void request(const MotionRequest& request);
  /// Torque on/off for all servos from the next step; `on` also clears the safety latches.
  void set_torque(bool on);
  /// Copies the latest published status (updated every tick the lock is free). Any thread.
  ControllerStatus status() const;

  const MotionManager& motion() const noexcept { return motion_; }
  const SafetyLayer& safety() const noexcept { return safety_; }
  const AttitudeEstimator& attitude() const noexcept { return attitude_; }
  std::int64_t period_ns() const noexcept { return period_ns_; }

 private:
  void take_inbox() noexcept;

  std::int64_t period_ns_;
  AttitudeEstimator& attitude_;
  SafetyLayer safety_;
  MotionManager motion_;
  hal::CommandFrame commands_{};
  bool torque_on_ = true;

  // Inbox from other threads (fixed capacity, no allocation).
  mutable std::mutex inbox_mutex_;
  std::array<MotionRequest, 8> inbox_{};
  std::size_t inbox_size_ = 0;
  std::uint32_t dropped_ = 0;
  bool torque_change_pending_ = false;
  bool torque_change_on_ = true;

  // Published status.
  mutable std::mutex status_mutex_;
  ControllerStatus published_{};
};

}  // namespace stride::fw
