// The speed ramp's mechanics without a simulation (ramp_direction.hpp, issue 44 point 5): the
// levels and their commands and windows, the patience, and the straightness limits, each on
// walking frames made up for the case.
#include "stride/optimiser/tasks/ramp_direction.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <vector>

namespace stride::opt {
namespace {

constexpr std::array<double, 3> kForward = {1.0, 0.0, 0.0}, kLeft = {0.0, 1.0, 0.0},
                                kTurnLeft = {0.0, 0.0, 1.0}, kTurnRight = {0.0, 0.0, -1.0};
constexpr double kDeg = std::numbers::pi / 180.0;

/// walk-ramp.json's settings: start 2 s, increment 0.1, hold 4 s, measure 3 s, 10 levels,
/// patience 2, drift ratio 0.1, heading 10 deg, turn translation 0.1 m.
TaskConfig ramp_config() {
  TaskConfig c;
  c.ramp = {2.0, 0.1, 4.0, 3.0, 10, 2};
  c.max_drift_ratio = 0.1;
  c.max_heading_change_deg = 10.0;
  c.max_turn_translation_m = 0.1;
  return c;
}

RampLevel straight_at(double speed) {
  RampLevel level;
  level.speed = speed;
  return level;
}

TEST(RampDirection, LevelsRiseEveryHoldFromTheStartWithTheirCommandAndWindow) {
  const TaskConfig c = ramp_config();
  RampDirection ramp(c);
  EXPECT_EQ(ramp.level_at(0.0), 0);
  EXPECT_EQ(ramp.level_at(1.99), 0);
  EXPECT_EQ(ramp.level_at(2.0), 1);
  EXPECT_EQ(ramp.level_at(5.99), 1);
  EXPECT_EQ(ramp.level_at(6.0), 2);
  EXPECT_EQ(ramp.level_at(41.0), 10);
  EXPECT_DOUBLE_EQ(ramp.command_scale(1), 0.1);
  EXPECT_DOUBLE_EQ(ramp.command_scale(7), 0.7);
  EXPECT_DOUBLE_EQ(ramp.command_scale(13), 1.0);  // never beyond full scale
  // Level 2 holds from 6 s to 10 s and is measured over its last 3 s.
  EXPECT_FALSE(ramp.window_begun(2, 6.99));
  EXPECT_TRUE(ramp.window_begun(2, 7.0));
  // After max_levels the direction ends.
  ramp.begin_level(10);
  EXPECT_FALSE(ramp.ended());
  ramp.begin_level(11);
  EXPECT_TRUE(ramp.ended());
  EXPECT_DOUBLE_EQ(c.ramp.episode_s(), 42.0);
}

/// The levels a direction measures before it ends, for these speeds and this patience.
int levels_until_end(const std::vector<double>& speeds, int patience, double& best) {
  TaskConfig c = ramp_config();
  c.ramp.patience = patience;
  RampDirection ramp(c);
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
  TaskConfig c = ramp_config();
  RampDirection still(c);
  still.end_level(1, straight_at(0.0));
  EXPECT_FALSE(still.ended());
  still.end_level(2, straight_at(-0.01));
  EXPECT_TRUE(still.ended());
  EXPECT_FALSE(still.counted());
  EXPECT_EQ(still.best().speed, 0.0);
}

TEST(RampDirection, ACrookedLevelEndsTheDirectionAndKeepsTheBestStraightOne) {
  const TaskConfig c = ramp_config();
  RampDirection first(c);
  RampLevel crooked = straight_at(0.5);
  crooked.straight = false;
  first.end_level(1, crooked);
  EXPECT_TRUE(first.ended());
  EXPECT_TRUE(first.crooked_first());
  EXPECT_FALSE(first.counted());

  RampDirection later(c);
  later.end_level(1, straight_at(0.1));
  later.end_level(2, crooked);
  EXPECT_TRUE(later.ended());
  EXPECT_FALSE(later.crooked_first());
  EXPECT_TRUE(later.counted());
  EXPECT_DOUBLE_EQ(later.best().speed, 0.1);
}

TEST(RampDirection, ATranslationsSpeedIsAlongItsAxisAndItsDriftSinceTheDirectionsStart) {
  const TaskConfig c = ramp_config();
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
  TaskConfig off = c;
  off.max_drift_ratio = -1.0;
  off.max_heading_change_deg = -1.0;
  EXPECT_TRUE(measure_ramp_level(start, {0, 0, 0}, {0.1, 0.5, 1.0}, kForward, off).straight);
}

TEST(RampDirection, ATurnsSpeedIsItsYawRateTheCommandedWayAndItsTranslationIsLimited) {
  const TaskConfig c = ramp_config();
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
