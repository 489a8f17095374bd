// Footstep planner and velocity handling: command scaling, turning factor, acceleration
// limits, step limits and the collision margin (igus.md 2.2, 2.3).
#include "stride/firmware/walk/footstep_planner.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace stride::fw::walk {
namespace {

const WalkParameters kP = default_walk_parameters();

TEST(WalkFootstepPlanner, ScalesTheNormalisedCommandByTheLimits) {
  PlanarVector v = scale_command({1.0, 0.0, 0.0}, kP);
  EXPECT_DOUBLE_EQ(v.x, 0.3);
  v = scale_command({-1.0, 0.0, 0.0}, kP);
  EXPECT_DOUBLE_EQ(v.x, -0.027);
  v = scale_command({0.0, 0.5, 0.0}, kP);
  EXPECT_DOUBLE_EQ(v.y, 0.005);
  v = scale_command({5.0, std::nan(""), -3.0}, kP);  // clamped, NaN -> 0
  EXPECT_TRUE(std::isfinite(v.x));
  EXPECT_EQ(v.y, 0.0);
  EXPECT_DOUBLE_EQ(v.angle, -0.8);
}

TEST(WalkFootstepPlanner, TurningSlowsThePlanarSpeed) {
  // f = 1 - |w|/0.6: w = 0.3 -> f = 0.5 -> |v| <= 0.15.
  PlanarVector v = scale_command({1.0, 0.0, 0.375}, kP);
  EXPECT_NEAR(v.angle, 0.3, 1e-12);
  EXPECT_NEAR(v.x, 0.15, 1e-12);
  // Past the turning factor the planar speed is 0, never reversed.
  v = scale_command({1.0, 1.0, 1.0}, kP);
  EXPECT_EQ(v.x, 0.0);
  EXPECT_EQ(v.y, 0.0);
}

TEST(WalkFootstepPlanner, AccelerationLimitsAndTheHighSpeedSet) {
  const PlanarVector target{0.3, 0.01, 0.8};
  PlanarVector v = accelerate({0.0, 0.0, 0.0}, target, 0.85, kP);
  EXPECT_NEAR(v.x, 0.3, 1e-12);  // 1.5 * 0.85 > 0.3
  EXPECT_NEAR(v.y, 0.01, 1e-12);
  v = accelerate({0.07, 0.0, 0.0}, target, 0.85, kP);  // above velocity_high: 0.08/s
  EXPECT_NEAR(v.x, 0.07 + 0.08 * 0.85, 1e-12);
  v = accelerate({0.0, 0.0, 0.0}, {0.0, 0.045, 0.0}, 0.5, kP);
  EXPECT_NEAR(v.y, 0.0225, 1e-12);
}

TEST(WalkFootstepPlanner, StepLimitsHoldRelativeToTheSupportFoot) {
  const Pose2 left{0.0, 0.105, 0.0}, right{0.0, -0.105, 0.0};
  // Far forward: x clamped to x_max.
  Pose2 d = plan_swing_destination(Foot::kLeft, left, right, {1.0, 0.0, 0.0}, kP);
  Pose2 rel = relative(right, d);
  EXPECT_NEAR(rel.x, 0.10, 1e-12);
  EXPECT_NEAR(rel.y, 0.21, 1e-12);
  // Far backward: x_min.
  d = plan_swing_destination(Foot::kRight, right, left, {-1.0, 0.0, 0.0}, kP);
  rel = relative(left, d);
  EXPECT_NEAR(rel.x, -0.10, 1e-12);
  EXPECT_NEAR(rel.y, -0.21, 1e-12);
  // A normal step: x = v in steady state from a side-by-side stance is 1.5 v.
  d = plan_swing_destination(Foot::kLeft, left, right, {0.05, 0.0, 0.0}, kP);
  EXPECT_NEAR(relative(right, d).x, 0.075, 1e-12);
}

TEST(WalkFootstepPlanner, OutwardAngleLimitsAndTheCollisionMargin) {
  const Pose2 left{0.0, 0.105, 0.0}, right{0.0, -0.105, 0.0};
  // Turning right while the left foot swings is inward: angle clamped to angle_min = 0.
  Pose2 d = plan_swing_destination(Foot::kLeft, left, right, {0.0, 0.0, -0.8}, kP);
  EXPECT_NEAR(relative(right, d).theta, 0.0, 1e-12);
  // Turning left: at most angle_max, and the feet stay >= 0.16 + 0.1075 |theta| apart.
  d = plan_swing_destination(Foot::kLeft, left, right, {0.0, 0.0, 0.8}, kP);
  Pose2 rel = relative(right, d);
  EXPECT_NEAR(rel.theta, 0.262, 1e-12);
  EXPECT_GE(rel.y, 0.16 + 0.1075 * 0.262 - 1e-12);
  // Stepping inward (right foot swings towards the left): y raised to the margin.
  d = plan_swing_destination(Foot::kRight, right, left, {0.0, 0.5, 0.0}, kP);
  rel = relative(left, d);
  EXPECT_NEAR(rel.y, -0.16, 1e-12);
  // A crossed bound (y_max below the margin) keeps the margin.
  WalkParameters p = kP;
  p.step_limits.y_max = 0.15;
  d = plan_swing_destination(Foot::kLeft, left, right, {0.0, 0.0, 0.0}, p);
  EXPECT_NEAR(relative(right, d).y, 0.16, 1e-12);
}

TEST(WalkFootstepPlanner, SupportPointsAndTorsoDestination) {
  const Pose2 left{0.0, 0.105, 0.0}, right{0.0, -0.105, 0.0};
  const Pose2 sl = support_point(Foot::kLeft, left, kP);
  const Pose2 sr = support_point(Foot::kRight, right, kP);
  EXPECT_NEAR(sl.x, 0.072, 1e-12);
  EXPECT_NEAR(sl.y, 0.155, 1e-12);
  EXPECT_NEAR(sr.y, -0.155, 1e-12);
  const Pose2 torso = torso_between(left, right, kP);
  EXPECT_NEAR(torso.x, 0.072, 1e-12);
  EXPECT_NEAR(torso.y, 0.0, 1e-12);
  const Pose2 closing = plan_closing_step(Foot::kRight, {0.3, 0.2, 0.5}, kP);
  const Pose2 rel = relative({0.3, 0.2, 0.5}, closing);
  EXPECT_NEAR(rel.x, 0.0, 1e-12);
  EXPECT_NEAR(rel.y, -0.21, 1e-12);
  EXPECT_NEAR(rel.theta, 0.0, 1e-12);
}

}  // namespace
}  // namespace stride::fw::walk
