// Leg kinematics of the igus leg: zero-pose geometry against the URDF, FK/IK round trip over
// the reachable workspace (0.1 mm, 0.1 mrad), smooth flagged clamping, never NaN.
#include "stride/firmware/walk/leg_kinematics.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <utility>

#include <gtest/gtest.h>

namespace stride::fw::walk {
namespace {

TEST(WalkLegKinematics, ZeroPoseMatchesUrdfGeometry) {
  // igus.md 1.1 derived geometry: ankle crossing at (0.00835, +-0.055, -0.5238).
  for (LegSide side : {LegSide::kLeft, LegSide::kRight}) {
    const LegKinematics leg(side);
    const Pose3 pose = leg.forward({});
    const double sign = static_cast<int>(side);
    EXPECT_NEAR(pose.position.x(), 0.00835, 1e-9);
    EXPECT_NEAR(pose.position.y(), sign * 0.055, 1e-9);
    EXPECT_NEAR(pose.position.z(), -0.5238, 1e-9);
    EXPECT_TRUE(pose.rotation.isIdentity(1e-12));
    const Eigen::Vector3d hip = leg.hip_point(0.0);
    EXPECT_NEAR(hip.x(), 0.00285, 1e-9);
    EXPECT_NEAR(hip.z(), -0.1238, 1e-9);
  }
}

TEST(WalkLegKinematics, HipYawMovesTheHipOnACircle) {
  // The yaw axis is 23 mm behind the roll/pitch crossing: yawing moves the hip sideways.
  const LegKinematics leg(LegSide::kLeft);
  const Eigen::Vector3d hip = leg.hip_point(0.5);
  EXPECT_NEAR(hip.x(), -0.02025 + 0.0231 * std::cos(0.5), 1e-12);
  EXPECT_NEAR(hip.y(), 0.055 + 0.0231 * std::sin(0.5), 1e-12);
}

TEST(WalkLegKinematics, RoundTripOverTheReachableWorkspace) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> yaw(-0.7, 0.7), roll(-0.5, 0.5), pitch(-1.5, 0.8),
      knee(0.05, 2.4), ankle_pitch(-1.2, 1.0), ankle_roll(-0.6, 0.6);
  int tested = 0;
  double worst_position = 0.0, worst_angle = 0.0;
  for (LegSide side : {LegSide::kLeft, LegSide::kRight}) {
    const LegKinematics leg(side);
    for (int i = 0; i < 3000; ++i) {
      const LegJoints q{yaw(rng),  roll(rng),        pitch(rng),
                        knee(rng), ankle_pitch(rng), ankle_roll(rng)};
      const Pose3 target = leg.forward(q);
      const double reach = (leg.hip_point(q.hip_yaw) - target.position).norm();
      if (reach > leg.reach_max() || reach < leg.reach_min()) continue;
      // The walking branch: the hip above the ankle in the foot frame (|ankle roll| < pi/2
      // about the foot's own axes); the other branch reaches the same pose with flipped joints.
      const Eigen::Vector3d hip_in_foot =
          target.rotation.transpose() * (leg.hip_point(q.hip_yaw) - target.position);
      if (hip_in_foot.z() < 0.02) continue;
      const LegIkResult ik = leg.inverse(target);
      ASSERT_FALSE(ik.clamped) << "reach " << reach;
      const Pose3 back = leg.forward(ik.joints);
      worst_position = std::max(worst_position, (back.position - target.position).norm());
      const Eigen::AngleAxisd error(back.rotation.transpose() * target.rotation);
      worst_angle = std::max(worst_angle, std::abs(error.angle()));
      const LegJoints& r = ik.joints;
      for (auto [a, b] : {std::pair{r.hip_yaw, q.hip_yaw},
                          {r.hip_roll, q.hip_roll},
                          {r.hip_pitch, q.hip_pitch},
                          {r.knee, q.knee},
                          {r.ankle_pitch, q.ankle_pitch},
                          {r.ankle_roll, q.ankle_roll}}) {
        ASSERT_NEAR(a, b, 1e-4) << "sample " << i << " q " << q.hip_yaw << " " << q.hip_roll << " "
                                << q.hip_pitch << " " << q.knee << " " << q.ankle_pitch << " "
                                << q.ankle_roll << " ik " << r.hip_yaw << " " << r.hip_roll << " "
                                << r.hip_pitch << " " << r.knee << " " << r.ankle_pitch << " "
                                << r.ankle_roll;
      }
      ++tested;
    }
  }
  std::printf("  %d poses: worst position error %.3g m, worst orientation error %.3g rad\n", tested,
              worst_position, worst_angle);
  EXPECT_GT(tested, 2000);
  EXPECT_LT(worst_position, 1e-4);  // 0.1 mm
  EXPECT_LT(worst_angle, 1e-4);     // 0.1 mrad
}

TEST(WalkLegKinematics, UnreachableTargetsAreClampedSmoothlyAndFlagged) {
  const LegKinematics leg(LegSide::kRight);
  Pose3 target;
  double previous_knee = 10.0;
  double previous_z = 0.0;
  bool first = true;
  for (double z = -0.45; z > -1.5; z -= 0.001) {
    target.position = Eigen::Vector3d(0.0285, -0.055, z);
    const LegIkResult ik = leg.inverse(target);
    const auto& q = ik.joints;
    for (double v : {q.hip_yaw, q.hip_roll, q.hip_pitch, q.knee, q.ankle_pitch, q.ankle_roll}) {
      ASSERT_TRUE(std::isfinite(v));
    }
    const double reach = (leg.hip_point(0.0) - target.position).norm();
    EXPECT_EQ(ik.clamped, reach > leg.reach_max());
    // Knee straightens monotonically and without jumps; never past the stretched leg.
    if (!first) {
      EXPECT_LE(q.knee, previous_knee + 1e-12);
      EXPECT_LT(previous_knee - q.knee, 0.05);
    }
    EXPECT_GE(q.knee, std::atan2(0.0055, 0.2) - 1e-12);
    previous_knee = q.knee;
    previous_z = z;
    first = false;
  }
  (void)previous_z;
  // Far beyond reach the foot ends within the soft band of full stretch.
  target.position = Eigen::Vector3d(0.0285, -0.055, -2.0);
  const LegIkResult far = leg.inverse(target);
  EXPECT_TRUE(far.clamped);
  const double reached =
      (leg.hip_point(far.joints.hip_yaw) - leg.forward(far.joints).position).norm();
  EXPECT_NEAR(reached, leg.reach_max() + LegKinematics::kSoftBand, 1e-6);
}

TEST(WalkLegKinematics, TooCloseAndNonFiniteTargetsStayFinite) {
  const LegKinematics leg(LegSide::kLeft);
  Pose3 target;
  target.position = leg.hip_point(0.0) + Eigen::Vector3d(0.0, 0.0, -0.01);
  LegIkResult ik = leg.inverse(target);
  EXPECT_TRUE(ik.clamped);
  EXPECT_LE(ik.joints.knee, LegKinematics::kKneeMax + 1e-9);
  EXPECT_TRUE(std::isfinite(ik.joints.ankle_pitch));
  target.position = leg.hip_point(0.0);  // distance 0
  ik = leg.inverse(target);
  EXPECT_TRUE(ik.clamped);
  EXPECT_TRUE(std::isfinite(ik.joints.hip_pitch));
  target.position.x() = std::nan("");
  ik = leg.inverse(target);
  EXPECT_TRUE(ik.clamped);
  EXPECT_EQ(ik.joints.knee, 0.0);
}

}  // namespace
}  // namespace stride::fw::walk
