// FallProtection: the pose and the stiffness the motion manager commands while a predicted fall
// happens (MotionState::kFalling), so that the arms meet the ground first, the bent knees lower
// the centre of mass, and the servos, soft and torque-limited, are not back-driven at full
// torque when the robot lands.
//
// Pose (URDF joint angles, stand_pose.hpp's order): both legs crouch (fall.hip_pitch_rad,
// fall.knee_rad, fall.ankle_pitch_rad; the rolls and yaws of the stand pose); falling forward
// both shoulder pitches go to fall.arm_forward_rad (arms ahead of the torso: a negative shoulder
// pitch swings the arm forward), falling backward to fall.arm_backward_rad, falling to a side
// the arm on that side rolls out by fall.arm_side_roll_rad; elbows at fall.elbow_rad.
// Stiffness: P gain fall.gain (0-100, as the scripts' gains), torque limit fall.torque_limit,
// moving speed 0 (the servo's maximum). Past fall.relax_tilt_rad the torque goes off (relaxed,
// as NUbots' FallingRelaxPlanner does), and from the moment the fall is detected it stays off
// for fall.relax_time_s: an MX servo whose torque is on brakes a back-driven motor (back-EMF) with
// more than its stall torque at any P gain, one whose torque is off does not. fall.protect 0
// switches the protection off (the robot then goes on with what it did until the fall is detected,
// as before). Figures and their sources: firmware/src/FALLING.md. Real-time: command() allocates
// nothing.
#pragma once

#include "stride/firmware/fall_predictor.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/hal/command_frame.hpp"

namespace stride::fw {

class FallProtection {
 public:
  explicit FallProtection(ParameterStore& params);

  bool enabled() const noexcept { return params_.value(protect_) != 0.0; }
  /// Seconds the pose is held after the prediction cleared without a fall.
  double hold_time_s() const noexcept { return params_.value(hold_time_); }
  /// Tilt beyond which a falling robot relaxes (torque off) [rad].
  double relax_tilt_rad() const noexcept { return params_.value(relax_tilt_); }
  /// Seconds a relaxed robot stays relaxed once the fall is detected (through the impact).
  double relax_time_s() const noexcept { return params_.value(relax_time_); }
  /// Writes the protective pose and stiffness for a fall in `direction` into `out`; `relaxed`:
  /// the same targets with the torque off.
  void command(FallDirection direction, bool relaxed, hal::CommandFrame& out) const noexcept;

 private:
  ParameterStore& params_;
  ParamHandle protect_, hold_time_, gain_, torque_limit_, hip_pitch_, knee_, ankle_pitch_,
      arm_forward_, arm_backward_, arm_side_roll_, elbow_, relax_tilt_, relax_time_;
};

}  // namespace stride::fw
