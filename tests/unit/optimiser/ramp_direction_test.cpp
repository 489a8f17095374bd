// The speed ramp's mechanics without a simulation (ramp_direction.hpp, issue 44 point 5): the
// levels, their speeds, commands and windows, the end at the walk's limits (issue 41 point 3),
// the patience, and the straightness limits, each on walking frames made up for the case.
#include "stride/optimiser/tasks/ramp_direction.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

namespace stride::opt {
namespace {

constexpr std::array<double, 3> kForward = {1.0, 0.0, 0.0}, kBackward = {-1.0, 0.0, 0.0},
                                kLeft = {0.0, 1.0, 0.0}, kTurnLeft = {0.0, 0.0, 1.0},
                                kTurnRight = {0.0, 0.0, -1.0};
constexpr double kDeg = std::numbers::pi / 180.0;

/// walk-ramp.json's settings: start 2 s, 0.05 m/s and 0.2 rad/s per level, hold 4 s, measure
/// 3 s, 10 levels, patience 2, drift ratio 0.1, heading 10 deg, turn translation 0.1 m.
RampSettings ramp_config() {
  RampSettings c;
  c.timing.start_s = 2.0;
  c.timing.increment_mps = 0.05;
  c.timing.increment_radps = 0.2;
  c.timing.hold_s = 4.0;
  c.timing.measure_s = 3.0;
  c.timing.max_levels = 10;
  c.timing.patience = 2;
  c.straightness.max_drift_ratio = 0.1;
  c.straightness.max_heading_change_deg = 10.0;
  c.straightness.max_turn_translation_m = 0.1;
  return c;
}

RampLevel straight_at(double speed) {
  RampLevel level;
  level.speed = speed;
  return level;
}

/// The walk of firmware/config/stepping-turf-omni.json as far as the planner sees it: Ind_O with
/// 0.5 s steps, step limits x_max 0.15 m and angle_max 0.8 rad, velocity limits x_min -0.1 and
/// y +-0.06 m/step. Its planned top speeds: forward 0.15 / 0.5 = 0.3 m/s (the step limit),
/// backward 0.2 m/s, sideways 0.115 m/s (the inner foot at the collision margin beyond 0.05
/// m/step: (0.025 + 1.5 * 0.06) / (2 * 0.5)), turning 0.8 / (2 * 0.5) = 0.8 rad/s.
fw::walk::WalkParameters fast_walk() {
  fw::walk::WalkParameters p = fw::walk::default_walk_parameters();
  p.step_time = 0.5;
  p.step_limits.x_max = 0.15;
  p.step_limits.angle_max = 0.8;
  p.velocity_limits.x_min = -0.1;
  p.velocity_limits.y_min = -0.06;
  p.velocity_limits.y_max = 0.06;
  return p;
}

TEST(RampDirection, LevelsRiseEveryHoldFromTheStartWithTheirSpeedAndWindow) {
  const RampSettings c = ramp_config();
  RampDirection ramp(c, kForward), turn(c, kTurnLeft);
  EXPECT_EQ(ramp.level_at(0.0), 0);
  EXPECT_EQ(ramp.level_at(1.99), 0);
  EXPECT_EQ(ramp.level_at(2.0), 1);
  EXPECT_EQ(ramp.level_at(5.99), 1);
  EXPECT_EQ(ramp.level_at(6.0), 2);
  EXPECT_EQ(ramp.level_at(41.0), 10);
  // A level is a speed: 0.05 m/s per level forward, 0.2 rad/s per level turning.
  EXPECT_DOUBLE_EQ(ramp.level_speed(1), 0.05);
  EXPECT_DOUBLE_EQ(ramp.level_speed(7), 0.35);
  EXPECT_DOUBLE_EQ(turn.level_speed(3), 0.6000000000000001);
  // Level 2 holds from 6 s to 10 s and is measured over its last 3 s.
  EXPECT_FALSE(ramp.window_begun(2, 6.99));
  EXPECT_TRUE(ramp.window_begun(2, 7.0));
  // After max_levels the direction ends (the walk could command more).
  RampSettings fast = c;
  fast.timing.increment_mps = 0.01;
  RampDirection slow(fast, kForward);
  EXPECT_GT(slow.begin_level(10, fast_walk()), 0.0);
  EXPECT_FALSE(slow.ended());
  EXPECT_EQ(slow.begin_level(11, fast_walk()), 0.0);
  EXPECT_TRUE(slow.ended());
  EXPECT_FALSE(slow.beyond_walk_limits());
  EXPECT_DOUBLE_EQ(c.timing.episode_s(), 42.0);
}

TEST(RampDirection, ALevelCommandsItsSpeedWithTheWalksLimitsAndEndsBeyondThem) {
  const RampSettings c = ramp_config();
  const fw::walk::WalkParameters walk = fast_walk();
  // Forward: command = speed * T / velocity.limits.x_max while the step limit does not bind.
  RampDirection forward(c, kForward);
  EXPECT_NEAR(forward.begin_level(1, walk), 0.05 * 0.5 / 0.3, 1e-11);
  EXPECT_NEAR(forward.begin_level(6, walk), 0.3 * 0.5 / 0.3, 1e-11);  // 0.15 m/step: the limit
  EXPECT_FALSE(forward.ended());
  EXPECT_EQ(forward.begin_level(7, walk), 0.0);  // 0.35 m/s: beyond the step limit
  EXPECT_TRUE(forward.ended());
  EXPECT_TRUE(forward.beyond_walk_limits());
  EXPECT_FALSE(forward.counted());
  // Backward: of |velocity.limits.x_min| = 0.1 m/step, up to 0.2 m/s.
  RampDirection backward(c, kBackward);
  EXPECT_NEAR(backward.begin_level(2, walk), 0.1 * 0.5 / 0.1, 1e-11);
  EXPECT_NEAR(backward.begin_level(4, walk), 1.0, 1e-11);
  EXPECT_EQ(backward.begin_level(5, walk), 0.0);
  EXPECT_TRUE(backward.beyond_walk_limits());
  // Sideways: 0.1 m/s is 0.05 m/step, the collision margin's edge; 0.15 m/s is beyond 0.115.
  RampDirection left(c, kLeft);
  EXPECT_NEAR(left.begin_level(1, walk), 0.05 * 0.5 / 0.06, 1e-11);
  EXPECT_NEAR(left.begin_level(2, walk), 0.1 * 0.5 / 0.06, 1e-11);
  EXPECT_EQ(left.begin_level(3, walk), 0.0);
  EXPECT_TRUE(left.beyond_walk_limits());
  // Turning: 0.75 c L / T = 0.2 rad/s at c = 0.2 / (0.75 * 0.8 / 0.5); 0.8 rad/s is the step
  // limit's cap (angle_max per step pair), reached at c = 0.8 / 1.2.
  RampDirection turn(c, kTurnRight);
  EXPECT_NEAR(turn.begin_level(1, walk), 0.2 / 1.2, 1e-11);
  EXPECT_NEAR(turn.begin_level(4, walk), 0.8 / 1.2, 1e-11);
  EXPECT_EQ(turn.begin_level(5, walk), 0.0);
  EXPECT_TRUE(turn.beyond_walk_limits());
  // Ind_O's sideways limit (0.01 m/step at 0.85 s: 0.012 m/s) cannot command the first level.
  RampDirection ind_o(c, kLeft);
  EXPECT_EQ(ind_o.begin_level(1, fw::walk::default_walk_parameters()), 0.0);
  EXPECT_TRUE(ind_o.ended());
  EXPECT_TRUE(ind_o.beyond_walk_limits());
}

TEST(RampDirection, ANormalisedRampCommandsItsShareWhateverTheWalk) {
  RampSettings c = ramp_config();
  c.timing.increment = 0.1;  // issue 32's ramp, as its run.json files give it
  RampDirection ramp(c, kLeft);
  const fw::walk::WalkParameters ind_o = fw::walk::default_walk_parameters();
  EXPECT_DOUBLE_EQ(ramp.level_speed(7), 0.7);
  EXPECT_DOUBLE_EQ(ramp.begin_level(1, ind_o), 0.1);
  EXPECT_DOUBLE_EQ(ramp.begin_level(7, ind_o), 0.7);
  EXPECT_DOUBLE_EQ(ramp.begin_level(10, ind_o), 1.0);
  EXPECT_FALSE(ramp.ended());
  c.timing.max_levels = 13;
  EXPECT_DOUBLE_EQ(ramp.begin_level(13, ind_o), 1.0);  // never beyond full scale
  EXPECT_FALSE(ramp.beyond_walk_limits());
}

/// The levels a direction measures before it ends, for these speeds and this patience.
int levels_until_end(const std::vector<double>& speeds, int patience, double& best) {
  RampSettings c = ramp_config();
  c.timing.patience = patience;
  RampDirection ramp(c, kForward);
  int level = 0;
  for (const double speed : speeds) {
    ramp.end_level(++level, straight_at(speed));
    if (ramp.ended()) break;
  }
  best = ramp.best().speed;
  return ramp.ended() ? level : -1;
}

TEST(RampDirection, PatienceLevelsInARowNoFasterThanTheBestEndTheDirection) {
  double best = 0.0;
  // No faster, then faster (the count starts again), then twice no faster: ends at level 6.
  const std::vector<double> speeds = {0.10, 0.20, 0.15, 0.25, 0.25, 0.24, 0.30};
  EXPECT_EQ(levels_until_end(speeds, 2, best), 6);
  EXPECT_DOUBLE_EQ(best, 0.25);
  EXPECT_EQ(levels_until_end(speeds, 1, best), 3);
  EXPECT_DOUBLE_EQ(best, 0.20);
  EXPECT_EQ(levels_until_end(speeds, 3, best), -1);  // still going after all seven
  EXPECT_DOUBLE_EQ(best, 0.30);
  // A direction that never moves counts nothing and ends after `patience` levels.
  RampSettings c = ramp_config();
  RampDirection still(c, kForward);
  still.end_level(1, straight_at(0.0));
  EXPECT_FALSE(still.ended());
  still.end_level(2, straight_at(-0.01));
  EXPECT_TRUE(still.ended());
  EXPECT_FALSE(still.counted());
  EXPECT_EQ(still.best().speed, 0.0);
}

TEST(RampDirection, ACrookedLevelEndsTheDirectionAndKeepsTheBestStraightOne) {
  const RampSettings c = ramp_config();
  RampDirection first(c, kForward);
  RampLevel crooked = straight_at(0.5);
  crooked.straight = false;
  first.end_level(1, crooked);
  EXPECT_TRUE(first.ended());
  EXPECT_TRUE(first.crooked_first());
  EXPECT_FALSE(first.counted());

  RampDirection later(c, kForward);
  later.end_level(1, straight_at(0.1));
  later.end_level(2, crooked);
  EXPECT_TRUE(later.ended());
  EXPECT_FALSE(later.crooked_first());
  EXPECT_TRUE(later.counted());
  EXPECT_DOUBLE_EQ(later.best().speed, 0.1);
}

TEST(RampDirection, ATranslationsSpeedIsAlongItsAxisAndItsDriftSinceTheDirectionsStart) {
  const RampSettings c = ramp_config();
  const PlanarPose start{0.0, 0.0, 0.0};
  // 0.3 m forward over the 3 s window: 0.1 m/s; 2 cm aside after 0.6 m: drift 0.033.
  RampLevel l = measure_ramp_level(start, {0.3, 0.0, 0.0}, {0.6, 0.02, 0.0}, kForward, c);
  EXPECT_NEAR(l.speed, 0.1, 1e-12);
  EXPECT_NEAR(l.drift_ratio, 0.02 / 0.6, 1e-12);
  EXPECT_TRUE(l.straight);
  // 7 cm aside after 0.6 m: 0.117 > 0.1.
  l = measure_ramp_level(start, {0.3, 0.0, 0.0}, {0.6, 0.07, 0.0}, kForward, c);
  EXPECT_NEAR(l.drift_ratio, 0.07 / 0.6, 1e-12);
  EXPECT_FALSE(l.straight);
  // Below 0.5 m walked the drift is taken against 0.5 m: 4 cm after 0.2 m is 0.08.
  l = measure_ramp_level(start, {0.1, 0.0, 0.0}, {0.2, 0.04, 0.0}, kForward, c);
  EXPECT_NEAR(l.drift_ratio, 0.08, 1e-12);
  EXPECT_TRUE(l.straight);
  // The heading since the direction's start: 9 deg passes, 11 deg does not.
  EXPECT_TRUE(measure_ramp_level(start, {0.3, 0, 0}, {0.6, 0, 9 * kDeg}, kForward, c).straight);
  l = measure_ramp_level(start, {0.3, 0, 0}, {0.6, 0, 11 * kDeg}, kForward, c);
  EXPECT_NEAR(l.heading_change_rad, 11 * kDeg, 1e-12);
  EXPECT_FALSE(l.straight);
  // Sideways to the left: along is +y, a forward creep is the drift.
  l = measure_ramp_level(start, {0.0, 0.2, 0.0}, {0.03, 0.5, 0.0}, kLeft, c);
  EXPECT_NEAR(l.speed, 0.1, 1e-12);
  EXPECT_NEAR(l.drift_ratio, 0.06, 1e-12);
  EXPECT_TRUE(l.straight);
  // Walking backwards on a forward command is a negative speed.
  EXPECT_LT(measure_ramp_level(start, {0.0, 0, 0}, {-0.1, 0, 0}, kForward, c).speed, 0.0);
  // With the limits off (negative) nothing is crooked.
  RampSettings off = c;
  off.straightness.max_drift_ratio = -1.0;
  off.straightness.max_heading_change_deg = -1.0;
  EXPECT_TRUE(measure_ramp_level(start, {0, 0, 0}, {0.1, 0.5, 1.0}, kForward, off).straight);
}

TEST(RampDirection, ATurnsSpeedIsItsYawRateTheCommandedWayAndItsTranslationIsLimited) {
  const RampSettings c = ramp_config();
  const PlanarPose start{0.0, 0.0, 0.0};
  // 0.9 rad anticlockwise over 3 s, moving 5 cm: 0.3 rad/s, within 0.1 m.
  RampLevel l = measure_ramp_level(start, {0.0, 0.0, 0.3}, {0.03, 0.04, 1.2}, kTurnLeft, c);
  EXPECT_NEAR(l.speed, 0.3, 1e-12);
  EXPECT_NEAR(l.translation_m, 0.05, 1e-12);
  EXPECT_TRUE(l.straight);
  // The same yaw change on a right turn command is the wrong way.
  EXPECT_NEAR(measure_ramp_level(start, {0, 0, 0.3}, {0, 0, 1.2}, kTurnRight, c).speed, -0.3,
              1e-12);
  // 12 cm of translation over the window: beyond 0.1 m.
  l = measure_ramp_level(start, {0.0, 0.0, -0.3}, {0.12, 0.0, -1.2}, kTurnRight, c);
  EXPECT_NEAR(l.speed, 0.3, 1e-12);
  EXPECT_FALSE(l.straight);
}

}  // namespace
}  // namespace stride::opt
