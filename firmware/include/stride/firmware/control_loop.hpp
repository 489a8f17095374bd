// ControlLoop: the fixed-rate cycle that ties a Robot (HAL) to the Controller:
//
//   woke = robot.sleep_until(next)      // HAL owns time; woke > next means overrun
//   robot.read(sensors)
//   params.apply_staged()               // staged parameter batches land at a tick boundary
//   commands = controller.step(sensors, woke)
//   robot.write(commands)
//   recorder.on_tick(...)               // optional: hands the cycle to the flight recorder
//   next = woke + 1                     // missed ticks are counted and skipped
//
// The loop itself allocates nothing and reads no clock; timing statistics come from the
// RealtimeRobot wrapper when the robot is paced by the real clock. A recorder (LoopRecorder)
// must keep the same rules: it copies the cycle into preallocated memory and returns.
#pragma once

#include <atomic>
#include <cstdint>

#include "stride/firmware/controller.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/hal/robot.hpp"

namespace stride::fw {

struct LoopCounters {
  std::uint64_t cycles = 0;         ///< cycles run
  std::uint64_t missed_ticks = 0;   ///< ticks skipped because a cycle overran
  std::uint64_t param_batches = 0;  ///< staged parameter batches applied
  hal::Tick last_tick = -1;
};

/// Hears every cycle of the loop on the control thread: the parameter changes applied at its
/// start (ParamChangeSink), then the sensors as read and the commands as sent. Real-time: an
/// implementation must not block, allocate, do I/O or throw.
class LoopRecorder : public ParamChangeSink {
 public:
  virtual void on_tick(hal::Tick tick, const hal::SensorFrame& sensors,
                       const hal::CommandFrame& commands) noexcept = 0;
  virtual ~LoopRecorder() = default;
};

class ControlLoop {
 public:
  ControlLoop(hal::Robot& robot, Controller& controller, ParameterStore& params)
      : robot_(robot), controller_(controller), params_(params) {}

  /// Runs one cycle. Real-time: yes.
  void run_once() noexcept;
  /// Runs `cycles` cycles (negative: forever) or until `stop` becomes true.
  void run(std::int64_t cycles, const std::atomic<bool>* stop = nullptr) noexcept;

  /// Attaches a recorder (null: none) before the loop runs; it must outlive the loop.
  void set_recorder(LoopRecorder* recorder) noexcept { recorder_ = recorder; }

  const LoopCounters& counters() const noexcept { return counters_; }
  const hal::SensorFrame& last_sensors() const noexcept { return sensors_; }
  const hal::CommandFrame& last_commands() const noexcept { return commands_; }

 private:
  hal::Robot& robot_;
  Controller& controller_;
  ParameterStore& params_;
  LoopRecorder* recorder_ = nullptr;
  hal::SensorFrame sensors_{};
  hal::CommandFrame commands_{};
  hal::Tick next_ = 0;
  LoopCounters counters_{};
};

}  // namespace stride::fw
