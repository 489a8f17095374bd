// Arm swing (equations in arm_swing.hpp).
#include "stride/firmware/walk/arm_swing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stride::fw::walk {
namespace {

ArmPose blend(const ArmPose& a, const ArmPose& b, double weight_a) {
  const double wb = 1.0 - weight_a;
  return {weight_a * a.pitch + wb * b.pitch, weight_a * a.roll + wb * b.roll,
          weight_a * a.elbow + wb * b.elbow};
}

double roll_floor(const Pose2& foot_in_torso, double side) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  const double yaw_out = side * foot_in_torso.theta;
  return 5.0 * kDeg + std::max(0.0, yaw_out) / 2.0 +
         std::max(0.0, std::abs(foot_in_torso.y) - 0.04) / 0.02 * 6.0 * kDeg;
}

}  // namespace

ArmTargets arm_swing(double phase, Foot swing, const Pose2& left_foot_in_torso,
                     const Pose2& right_foot_in_torso, const WalkParameters& p) noexcept {
  double e = 0.5 * (1.0 - std::cos(std::numbers::pi * phase));
  if (swing == Foot::kLeft) e = 1.0 - e;
  ArmTargets out;
  out.left = blend(p.left_arm_start, p.left_arm_end, e);
  out.right = blend(p.right_arm_start, p.right_arm_end, 1.0 - e);
  out.left.roll = std::max(out.left.roll, roll_floor(left_foot_in_torso, 1.0));
  out.right.roll = std::min(out.right.roll, -roll_floor(right_foot_in_torso, -1.0));
  return out;
}

}  // namespace stride::fw::walk
