// Spline-walk footsteps: the command's scaling and combined limit, the acceleration limits,
// the forward step, the side step on the outer foot only, the turn on both feet, and the
// collision rule.
#include "stride/firmware/walk/spline_footsteps.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace stride::fw::walk {
namespace {

SplineWalkParameters params() {
  return default_spline_walk_parameters();
}

TEST(SplineFootsteps, FullCommandsReachTheStepLimitsAtTheStepRate) {
  const auto p = params();
  const double steps_per_s = 2.0 * p.frequency;
  EXPECT_DOUBLE_EQ(command_velocity({1, 0, 0}, p).x, p.max_step_forward * steps_per_s);
  EXPECT_DOUBLE_EQ(command_velocity({-1, 0, 0}, p).x, -p.max_step_backward * steps_per_s);
  EXPECT_DOUBLE_EQ(command_velocity({0, 1, 0}, p).y, p.max_step_side * p.frequency);
  EXPECT_DOUBLE_EQ(command_velocity({0, 0, -1}, p).turn, -p.max_turn * p.frequency);
}

TEST(SplineFootsteps, ACombinedCommandIsScaledOntoTheUnitBallAndNaNIsZero) {
  const auto p = params();
  const WalkVelocity v = command_velocity({1, 1, 0}, p);
  const WalkVelocity x = command_velocity({1, 0, 0}, p);
  EXPECT_NEAR(v.x, x.x / std::sqrt(2.0), 1e-12);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const WalkVelocity n = command_velocity({nan, 5.0, nan}, p);
  EXPECT_EQ(n.x, 0.0);
  EXPECT_EQ(n.turn, 0.0);
  EXPECT_DOUBLE_EQ(n.y, p.max_step_side * p.frequency);  // clamped to 1
}

TEST(SplineFootsteps, AccelerationIsLimitedPerAxis) {
  auto p = params();
  p.acceleration_x = 0.5;
  p.acceleration_y = 0.2;
  p.acceleration_turn = 1.0;
  const WalkVelocity v = accelerate({}, {1.0, -1.0, 1.0}, 0.1, p);
  EXPECT_NEAR(v.x, 0.05, 1e-12);
  EXPECT_NEAR(v.y, -0.02, 1e-12);
  EXPECT_NEAR(v.turn, 0.1, 1e-12);
  const WalkVelocity w = accelerate({0.3, 0, 0}, {0.31, 0, 0}, 1.0, p);
  EXPECT_DOUBLE_EQ(w.x, 0.31);  // reaches a near target exactly
}

TEST(SplineFootsteps, AForwardStepLandsTheStepLengthAheadAtTheStanceWidth) {
  const auto p = params();
  const Pose2 support{0.0, -0.1, 0.0};
  const Pose2 t = plan_spline_step(Foot::kLeft, support, {0.4, 0, 0}, 0.25, 0.0, {}, p);
  EXPECT_NEAR(t.x, 0.1, 1e-12);
  EXPECT_NEAR(t.y, -0.1 + p.foot_distance, 1e-12);
  EXPECT_NEAR(t.theta, 0.0, 1e-12);
}

TEST(SplineFootsteps, OnlyTheOuterFootStepsSideways) {
  const auto p = params();
  const WalkVelocity left{0.0, 0.2, 0.0};
  const double step_time = 0.25;
  // Walking left: the left foot opens by a cycle's travel, the right one closes to the width.
  const Pose2 open = plan_spline_step(Foot::kLeft, {0, -0.1, 0}, left, step_time, 0.0, {}, p);
  EXPECT_NEAR(open.y - (-0.1), p.foot_distance + 2.0 * 0.2 * step_time, 1e-12);
  const Pose2 close = plan_spline_step(Foot::kRight, open, left, step_time, 0.0, {}, p);
  EXPECT_NEAR(open.y - close.y, p.foot_distance, 1e-12);
  // Two steps moved both feet by one cycle's travel: v_y * 2T.
  EXPECT_NEAR(close.y - (-0.1), 2.0 * 0.2 * step_time, 1e-12);
}

TEST(SplineFootsteps, BothFeetTurnAndEachStepTurnsItsFootByTheCyclesTurn) {
  auto p = params();
  p.turn_inner_ratio = 0.5;
  const double step_time = 0.25, w = 1.2;  // rad/s: 0.6 rad per cycle
  const WalkVelocity turn{0.0, 0.0, w};
  Pose2 right{0.0, -0.1, 0.0};
  const Pose2 left = plan_spline_step(Foot::kLeft, right, turn, step_time, 0.0, {}, p);
  EXPECT_NEAR(left.theta - right.theta, 0.3, 1e-12);  // opened by half the cycle's turn
  const Pose2 right2 = plan_spline_step(Foot::kRight, left, turn, step_time, 0.0, {}, p);
  EXPECT_NEAR(right2.theta - right.theta, 0.6, 1e-12);  // the closing foot turned too
  EXPECT_NEAR(left.theta - right2.theta, -0.3, 1e-12);  // now toed in by half
  // Toe-out only (the seed's way): the closing step comes back to parallel.
  p.turn_inner_ratio = 0.0;
  const Pose2 l = plan_spline_step(Foot::kLeft, right, turn, step_time, 0.0, {}, p);
  const Pose2 r = plan_spline_step(Foot::kRight, l, turn, step_time, 0.0, {}, p);
  EXPECT_NEAR(l.theta, 0.6, 1e-12);
  EXPECT_NEAR(r.theta, l.theta, 1e-12);
}

TEST(SplineFootsteps, TheCollisionRuleKeepsTheSolesApartAndWidensWhenToedIn) {
  auto p = params();
  p.foot_distance = 0.14;
  const Pose2 support{0.0, 0.1, 0.0};
  // A capture offset pushing the right foot inward is stopped at the least distance.
  const Pose2 t = plan_spline_step(Foot::kRight, support, {}, 0.25, 0.0, {0.0, 0.2, 0.0}, p);
  EXPECT_NEAR(support.y - t.y, min_foot_distance(0.0, p), 1e-12);
  EXPECT_NEAR(min_foot_distance(0.0, p), 0.11 + p.foot_clearance, 1e-12);
  // Closing a left turn toes the feet in: the least distance grows with the toe's swing.
  const Pose2 c = plan_spline_step(Foot::kRight, support, {0, 0, 1.6}, 0.25, 0.0, {}, p);
  const double toe_in = support.theta - c.theta;  // left yaw - right yaw < 0
  ASSERT_LT(toe_in, 0.0);
  const Pose2 rel = relative(c, support);
  EXPECT_GE(rel.y + 1e-12, min_foot_distance(-toe_in, p) * std::cos(0.5 * toe_in) - 1e-3);
  EXPECT_GT(min_foot_distance(-toe_in, p), min_foot_distance(0.0, p));
}

TEST(SplineFootsteps, TheClosingStepIsParallelAtTheStanceWidth) {
  const auto p = params();
  const Pose2 support{0.3, 0.2, 0.4};
  const Pose2 t = plan_spline_closing_step(Foot::kRight, support, p);
  const Pose2 rel = relative(support, t);
  EXPECT_NEAR(rel.x, 0.0, 1e-12);
  EXPECT_NEAR(rel.y, -p.foot_distance, 1e-12);
  EXPECT_NEAR(rel.theta, 0.0, 1e-12);
}

}  // namespace
}  // namespace stride::fw::walk
