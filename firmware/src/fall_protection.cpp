// FallProtection implementation (see the header; figures in FALLING.md).
#include "stride/firmware/fall_protection.hpp"

#include "stride/firmware/stand_pose.hpp"

namespace stride::fw {

namespace {
// Servo indices (Dynamixel ID - 1), stand_pose.hpp's order.
constexpr std::size_t kRShoulderPitch = 0, kLShoulderPitch = 1, kRShoulderRoll = 2,
                      kLShoulderRoll = 3, kRElbow = 4, kLElbow = 5, kRHipPitch = 10,
                      kLHipPitch = 11, kRKnee = 12, kLKnee = 13, kRAnklePitch = 14,
                      kLAnklePitch = 15;
}  // namespace

FallProtection::FallProtection(ParameterStore& params) : params_(params) {
  protect_ =
      params.add({"fall.protect", ParamType::kBool, 1, 0, 1, "",
                  "take the protective pose and go soft when a fall is predicted", false, false});
  hold_time_ = params.add_real("fall.hold_time_s", 0.5, 0.0, 5.0, "s",
                               "pose held after a prediction that cleared without a fall");
  gain_ = params.add_real("fall.gain", 15.0, 0.0, 100.0, "1",
                          "servo gain (0-100) while falling: soft, yet quick enough to the pose");
  torque_limit_ = params.add_real("fall.torque_limit", 0.4, 0.0, 1.0, "1",
                                  "servo torque limit while falling (fraction of the maximum)");
  hip_pitch_ = params.add_real("fall.hip_pitch_rad", -0.7, -1.5, 0.0, "rad",
                               "hip pitch of the protective crouch (negative: thigh forward)");
  knee_ = params.add_real("fall.knee_rad", 1.4, 0.0, 2.2, "rad",
                          "knee of the protective crouch (positive: bent)");
  ankle_pitch_ = params.add_real("fall.ankle_pitch_rad", -0.7, -1.2, 0.5, "rad",
                                 "ankle pitch of the protective crouch");
  arm_forward_ = params.add_real("fall.arm_forward_rad", -1.3, -2.5, 0.5, "rad",
                                 "shoulder pitch falling forward (negative: arms ahead)");
  arm_backward_ = params.add_real("fall.arm_backward_rad", 1.3, -0.5, 2.5, "rad",
                                  "shoulder pitch falling backward (positive: arms behind)");
  arm_side_roll_ = params.add_real("fall.arm_side_roll_rad", 1.0, 0.0, 1.6, "rad",
                                   "outward shoulder roll of the arm on the side of the fall");
  elbow_ = params.add_real("fall.elbow_rad", -0.5, -2.6, 0.0, "rad",
                           "elbow while falling (slightly bent, so the arm gives on contact)");
  relax_tilt_ = params.add_real("fall.relax_tilt_rad", 1.6, 0.3, 1.6, "rad",
                                "tilt beyond which a falling robot switches its torque off");
  relax_time_ = params.add_real("fall.relax_time_s", 0.0, 0.0, 5.0, "s",
                                "torque off for this long after the fall is detected (impact)");
}

void FallProtection::command(FallDirection direction, bool relaxed,
                             hal::CommandFrame& out) const noexcept {
  std::array<double, hal::kServoCount> pose = kStandPoseRad;
  pose[kRHipPitch] = pose[kLHipPitch] = params_.value(hip_pitch_);
  pose[kRKnee] = pose[kLKnee] = params_.value(knee_);
  pose[kRAnklePitch] = pose[kLAnklePitch] = params_.value(ankle_pitch_);
  pose[kRElbow] = pose[kLElbow] = params_.value(elbow_);
  const double side_roll = params_.value(arm_side_roll_);
  switch (direction) {
    case FallDirection::kForward:
      pose[kRShoulderPitch] = pose[kLShoulderPitch] = params_.value(arm_forward_);
      break;
    case FallDirection::kBackward:
      pose[kRShoulderPitch] = pose[kLShoulderPitch] = params_.value(arm_backward_);
      break;
    case FallDirection::kRight:  // the right arm rolls out: negative roll
      pose[kRShoulderRoll] = kStandPoseRad[kRShoulderRoll] - side_roll;
      break;
    case FallDirection::kLeft:
      pose[kLShoulderRoll] = kStandPoseRad[kLShoulderRoll] + side_roll;
      break;
    case FallDirection::kNone:
      break;
  }
  const double p_gain = gain_to_p_register(params_.value(gain_));
  const double torque_limit = params_.value(torque_limit_);
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    hal::ServoCommand& c = out.servos[i];
    c.position_rad = pose[i];
    c.moving_speed_rad_s = 0.0;
    c.p_gain = p_gain;
    c.torque_limit = torque_limit;
    c.torque_enable = !relaxed;
  }
}

}  // namespace stride::fw
