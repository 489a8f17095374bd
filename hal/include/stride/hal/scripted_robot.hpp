// ScriptedRobot: a deterministic test HAL that feeds prepared sensor frames and records the
// commands it receives. It needs no clock (sleep_until returns at once) and no hardware.
//
// Used by unit and integration tests, and by `stride-fw --hal test` (wrapped in the real-clock
// RealtimeRobot) to run the firmware loop without a robot.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "stride/hal/robot.hpp"

namespace stride::hal {

class ScriptedRobot final : public Robot {
 public:
  struct Options {
    std::int64_t period_ns = 10'000'000;  ///< tick length reported by period_ns()
    /// Present positions follow the last goal positions at their moving speed (0 = at once),
    /// like an ideal servo; otherwise the prepared frames are returned unchanged.
    bool echo_commands = false;
    /// Commands recorded at most; later ones are counted but not stored (no allocation).
    std::size_t record_capacity = 4096;
  };

  /// `frames` are returned by read() in order, the last one repeating. Must not be empty.
  ScriptedRobot(Options options, std::vector<SensorFrame> frames);

  /// Makes sleep_until(tick) report a late wake-up at `woken` instead of `tick`.
  void inject_late_wakeup(Tick tick, Tick woken);

  std::int64_t period_ns() const noexcept override { return options_.period_ns; }
  Tick sleep_until(Tick tick) noexcept override;
  void read(SensorFrame& out) noexcept override;
  void write(const CommandFrame& commands) noexcept override;
  void set_torque_enable(bool enabled) noexcept override;
  const Diagnostics& diagnostics() const noexcept override { return diagnostics_; }

  const std::vector<CommandFrame>& recorded() const { return recorded_; }
  std::size_t writes() const { return writes_; }
  std::size_t reads() const { return reads_; }
  bool torque_enabled() const { return torque_enabled_; }

  /// A healthy robot standing still: IMU (0, 0, +9.81), every servo at `position_rad`.
  static SensorFrame standing_frame(const std::array<double, kServoCount>& position_rad = {});

 private:
  Options options_;
  std::vector<SensorFrame> frames_;
  std::vector<CommandFrame> recorded_;
  std::vector<std::pair<Tick, Tick>> late_wakeups_;
  CommandFrame last_command_{};
  bool have_command_ = false;
  std::array<double, kServoCount> echo_position_{};
  Tick current_tick_ = 0;
  std::size_t reads_ = 0;
  std::size_t writes_ = 0;
  bool torque_enabled_ = false;
  Diagnostics diagnostics_{};
};

}  // namespace stride::hal
