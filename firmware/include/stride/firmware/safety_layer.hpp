// SafetyLayer: the last stage before the HAL. Whatever the motion engines asked for, what
// leaves the controller is finite, inside the servo table's joint limits and the configured
// torque limit, and servos with persistent error flags are switched off. It also detects a
// fall from the IMU.
//
// Fall detection: tilt = angle between the torso z axis and the measured specific force
// (upright and still: accel = (0, 0, +9.81), tilt 0). The robot is "fallen" when the low-pass
// filtered tilt stays above safety.fall_tilt for safety.fall_ticks ticks, and "upright" again
// when it drops below safety.upright_tilt (the accelerometer alone, low-passed: whether the
// robot lies is a question for a still torso). Before that, FallPredictor (fall_predictor.hpp)
// sees a fall coming from the firmware's attitude estimate and its rate; the motion manager then
// protects the robot.
//
// Parameters: safety.max_torque_limit [0..1], safety.max_p_gain [register], safety.fall_tilt
// [rad], safety.upright_tilt [rad], safety.fall_ticks, safety.error_ticks (consecutive ticks
// of error flags before a servo's torque is switched off), safety.error_mask (which Dynamixel
// error bits count).
#pragma once

#include <array>
#include <cstdint>

#include "stride/firmware/fall_predictor.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/servo_table.hpp"
#include "stride/hal/command_frame.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw {

/// Cumulative counters of what the safety layer changed. Plain data, copyable.
struct SafetyReport {
  std::array<std::uint32_t, hal::kServoCount> limit_clamps{};  ///< ticks a target was clamped
  std::array<std::uint32_t, hal::kServoCount> nan_targets{};   ///< ticks a target was not finite
  std::array<bool, hal::kServoCount> torque_off_latched{};     ///< switched off for errors
  std::uint32_t torque_clamps = 0;  ///< ticks a torque limit or gain was reduced
  std::uint32_t falls = 0;          ///< upright -> fallen transitions
  bool fallen = false;              ///< current fall state
  double tilt_rad = 0.0;            ///< filtered torso tilt
  std::uint32_t predictions = 0;    ///< not falling -> falling predicted transitions
  bool falling = false;             ///< a fall is predicted now (FallPredictor)
  FallDirection fall_direction = FallDirection::kNone;
  double fall_tilt_rad = 0.0;  ///< the predictor's attitude: larger of |roll|, |pitch|
};

class SafetyLayer {
 public:
  SafetyLayer(ParameterStore& params, const ServoTable& servos);

  /// Updates the fall state from this tick's IMU and the attitude estimate (already updated
  /// with it; the fall predictor reads it). Real-time: yes.
  void observe(const hal::SensorFrame& sensors, const AttitudeEstimator& attitude) noexcept;

  /// Makes `commands` safe in place (clamps, NaN guard, torque limits, error torque-off).
  /// Real-time: yes.
  void apply(const hal::SensorFrame& sensors, hal::CommandFrame& commands) noexcept;

  /// Clears the error latches (console `torque on`), keeping the counters.
  void reset_latches() noexcept;

  bool fallen() const noexcept { return report_.fallen; }
  /// A fall is predicted (it has not happened yet, or is happening).
  bool falling() const noexcept { return report_.falling; }
  const SafetyReport& report() const noexcept { return report_; }

 private:
  ParameterStore& params_;
  const ServoTable& servos_;
  ParamHandle max_torque_limit_, max_p_gain_, fall_tilt_, upright_tilt_, fall_ticks_, error_ticks_,
      error_mask_;
  FallPredictor predictor_;
  SafetyReport report_{};
  std::array<double, hal::kServoCount> last_safe_{};
  std::array<bool, hal::kServoCount> have_last_safe_{};
  std::array<std::uint32_t, hal::kServoCount> error_run_{};
  std::uint32_t tilt_run_ = 0;
  bool tilt_initialised_ = false;
};

}  // namespace stride::fw
