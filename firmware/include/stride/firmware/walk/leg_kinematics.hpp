// LegKinematics: forward and inverse kinematics of one igus leg as built (URDF 56d80a1,
// igus.md 1.1), not the intersecting-axes simplification of NUbots (igus.md 2.6).
//
// Chain (trunk frame: x forward, y left, z up; all joint frames parallel to the trunk at zero):
//   hip yaw   (z) at Y0 = (-0.02025, +-0.055, -0.080)          [left +, right -]
//   hip roll  (x) and hip pitch (y) at Y0 + Rz(q_yaw) a, a = (0.0231, 0, -0.0438)
//                 (the yaw axis is 23 mm behind and 43.8 mm above the roll/pitch crossing)
//   knee      (y) 0.200 below the hip pitch axis (thigh l1 = (0, 0, -0.200))
//   ankle pitch (y) and roll (x) at shank l2 = (0.0055, 0, -0.200) from the knee
// Foot frame (URDF foot_link): origin at the ankle crossing,
//   R_foot = Rz(yaw) Rx(roll) Ry(pitch + knee + ankle_pitch) Rx(ankle_roll),
//   p_foot = Y0 + Rz(yaw) [a + Rx(roll) (Ry(pitch) l1 + Ry(pitch + knee) l2)].
// Joint angles are URDF angles [rad] (knee positive when bent); both legs share the axes.
//
// IK (closed form inside a fixed-point iteration on the hip yaw): for a yaw guess the hip
// crossing H is known; in the foot frame v = R_foot^T (H - p_foot) gives the ankle roll
// atan2(v_y, v_z); the sagittal two-link triangle |Ry(-knee) l1 + l2| = |v| gives the knee and
// ankle pitch; Rz(yaw) Rx(roll) Ry(pitch) = R_foot Rx(-ankle_roll) Ry(-knee - ankle_pitch) gives
// yaw, roll and pitch. The yaw depends on H only weakly (|a_xy| = 23 mm), so a few iterations
// reach 1e-12 rad. A hip-ankle distance outside the reachable band is clamped smoothly
// (exponential approach, C1) and flagged; the result is always finite.
#pragma once

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace stride::fw::walk {

enum class LegSide : int { kLeft = 1, kRight = -1 };

/// Leg joint angles [rad] in chain order.
struct LegJoints {
  double hip_yaw = 0.0;
  double hip_roll = 0.0;
  double hip_pitch = 0.0;
  double knee = 0.0;
  double ankle_pitch = 0.0;
  double ankle_roll = 0.0;
};

/// A rigid pose: rotation and position [m] in the trunk frame.
struct Pose3 {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

/// The igus leg's fixed geometry [m] (URDF 56d80a1).
struct LegGeometry {
  static constexpr double kHipYawX = -0.02025;
  static constexpr double kHipYawY = 0.055;  ///< left; the right leg mirrors it
  static constexpr double kHipYawZ = -0.080;
  static constexpr double kYawToHipX = 0.0231;
  static constexpr double kYawToHipZ = -0.0438;
  static constexpr double kThigh = 0.200;
  static constexpr double kShankZ = 0.200;
  static constexpr double kShankX = 0.0055;
  /// Ankle crossing above the ground the foot stands on: the tips of the 18 mm studs of the
  /// studded igus foot (igus.md 1.3: stud tips at z = -0.0565 in the foot frame; the seed's
  /// simulator and Stride's use the studded foot). The flat sole alone would be 0.039.
  static constexpr double kAnkleHeight = 0.0565;
  /// Hip roll/pitch crossing z in the trunk frame at any yaw.
  static constexpr double kHipZ = kHipYawZ + kYawToHipZ;
  /// Hip roll/pitch crossing x in the trunk frame at zero yaw.
  static constexpr double kHipX = kHipYawX + kYawToHipX;
};

/// Result of an IK solve.
struct LegIkResult {
  LegJoints joints;
  bool clamped = false;  ///< target out of reach: the hip-ankle distance was clamped
};

/// The trunk's rotation in the walk plane's frame: yawed by `yaw`, then pitched forward by
/// `pitch` [rad] (both walk engines put the feet into the trunk frame with it).
inline Eigen::Matrix3d trunk_rotation(double yaw, double pitch) noexcept {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}

class LegKinematics {
 public:
  explicit LegKinematics(LegSide side) noexcept;

  LegSide side() const noexcept { return side_; }

  /// Pose of the foot frame (ankle crossing, foot orientation) in the trunk frame.
  Pose3 forward(const LegJoints& q) const noexcept;
  /// Hip roll/pitch crossing in the trunk frame for a hip yaw [rad].
  Eigen::Vector3d hip_point(double hip_yaw) const noexcept;

  /// Joint angles that put the foot frame at `target` (trunk frame). Never NaN: non-finite
  /// input returns the zero pose, flagged.
  LegIkResult inverse(const Pose3& target) const noexcept;

  /// Hip-ankle distances [m] beyond which targets are clamped (the soft band starts here).
  double reach_max() const noexcept { return reach_max_ - kSoftBand; }
  double reach_min() const noexcept { return reach_min_ + kSoftBand; }

  /// Width of the smooth clamping band [m].
  static constexpr double kSoftBand = 0.004;
  /// Largest knee angle the IK plans for [rad] (the servo table allows 2.6).
  static constexpr double kKneeMax = 2.5;

 private:
  LegSide side_;
  Eigen::Vector3d yaw_origin_;
  double shank_length_;  ///< |l2|
  double shank_angle_;   ///< atan2(l2_x, -l2_z): knee angle of the fully stretched leg
  double reach_max_;     ///< l1 + |l2|
  double reach_min_;     ///< distance at kKneeMax
};

}  // namespace stride::fw::walk
