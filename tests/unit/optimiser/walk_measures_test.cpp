// Walk measures (issue 22): translations in the start's heading frame, yaw unwrapping, the
// walk-omni time line, its speed objective and constraints, and the per-direction table.
#include "stride/optimiser/tasks/walk_measures.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "stride/optimiser/run/direction_speeds.hpp"

namespace stride::opt {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(WalkMeasures, TranslationIsMeasuredInTheStartsHeadingFrame) {
  // Facing +y (yaw pi/2), moving 1 m along +y and 0.05 m towards -x (the robot's left).
  const PlanarPose a{1.0, 2.0, kPi / 2};
  const PlanarPose b{0.95, 3.0, kPi / 2 + 0.1};
  const Translation forward = measure_translation(a, b, 1.0, 0.0);
  EXPECT_NEAR(forward.along_m, 1.0, 1e-12);
  EXPECT_NEAR(forward.off_axis_m, 0.05, 1e-12);
  EXPECT_NEAR(forward.heading_change_rad, 0.1, 1e-12);
  EXPECT_NEAR(forward.drift_ratio(), 0.05, 1e-12);
  // The same move seen as a step to the right: along -0.05 m (the wrong way), off-axis 1 m.
  const Translation right = measure_translation(a, b, 0.0, -1.0);
  EXPECT_NEAR(right.along_m, -0.05, 1e-12);
  EXPECT_NEAR(right.off_axis_m, 1.0, 1e-12);
  // A short move is held against the 0.25 m floor.
  const Translation small = measure_translation({0, 0, 0}, {0.1, 0.01, 0}, 1.0, 0.0);
  EXPECT_NEAR(small.drift_ratio(), 0.01 / kDriftDistanceFloor, 1e-12);
}

TEST(WalkMeasures, YawTrackerUnwrapsFullTurns) {
  YawTracker t;
  t.reset(0.0);
  double wrapped = 0.0;
  for (int i = 1; i <= 1000; ++i) {
    wrapped = std::remainder(0.02 * i, 2.0 * kPi);
    t.update(wrapped);
  }
  EXPECT_NEAR(t.yaw(), 20.0, 1e-9);
}

TEST(WalkMeasures, OmniTimeLineRampsHoldsAndStopsEachSegment) {
  OmniTiming timing;  // start 4, ramp 1, hold 8, stop 2
  const OmniEpisode e(timing, 0.01);
  EXPECT_DOUBLE_EQ(e.duration_s(), 70.0);
  EXPECT_EQ(e.command(0), (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(e.command(399), (std::array<double, 3>{0, 0, 0}));
  EXPECT_NEAR(e.command(450)[0], 0.5, 1e-9);  // forward ramp, half way
  EXPECT_EQ(e.command(600), (std::array<double, 3>{1, 0, 0}));
  EXPECT_EQ(e.command(1400), (std::array<double, 3>{0, 0, 0}));   // forward stop
  EXPECT_EQ(e.command(1600), (std::array<double, 3>{-1, 0, 0}));  // backward hold
  EXPECT_EQ(e.command(2700), (std::array<double, 3>{0, 1, 0}));   // left
  EXPECT_EQ(e.command(3800), (std::array<double, 3>{0, -1, 0}));  // right
  EXPECT_EQ(e.command(4900), (std::array<double, 3>{0, 0, 1}));   // turn left
  EXPECT_EQ(e.command(6000), (std::array<double, 3>{0, 0, -1}));  // turn right
  EXPECT_EQ(e.command(6950), (std::array<double, 3>{0, 0, 0}));
}

TEST(WalkMeasures, OmniObjectiveIsTheBitBotsScoreAndConstraintsSumTheViolations) {
  OmniSegments s{};
  for (auto& seg : s) seg.measured = true;
  s[0].speed = 0.3;   // forward
  s[1].speed = 0.2;   // backward
  s[2].speed = 0.1;   // left
  s[3].speed = 0.05;  // right
  s[4].speed = 1.0;   // turn left
  s[5].speed = 0.5;   // turn right
  EXPECT_NEAR(omni_speed_objective(s), -(0.3 + 0.2 + 2 * 0.075 + 0.2 * 0.75), 1e-12);
  StraightnessLimits config;  // drift 0.1, heading 10 deg, turn translation 0.1 m
  EXPECT_EQ(omni_constraints(s, config), (std::array<double, 3>{0, 0, 0}));
  s[0].drift_ratio = 0.15;                       // 1.5 x the limit: -0.5
  s[2].drift_ratio = 0.3;                        // 3 x the limit: capped at -1
  s[1].heading_change_rad = 15.0 * kPi / 180.0;  // 1.5 x the limit: -0.5
  s[5].translation_m = 0.25;                     // 2.5 x the limit: capped at -1
  const auto c = omni_constraints(s, config);
  EXPECT_NEAR(c[0], -1.5, 1e-12);
  EXPECT_NEAR(c[1], -0.5, 1e-12);
  EXPECT_NEAR(c[2], -1.0, 1e-12);
  // A segment not reached (a fall before it) adds -1 to each of its constraints, whatever its
  // (unset) figures: falling earlier never lowers the violation.
  s[3].measured = false;
  s[4].measured = false;
  const auto fallen = omni_constraints(s, config);
  EXPECT_NEAR(fallen[0], -2.5, 1e-12);
  EXPECT_NEAR(fallen[1], -1.5, 1e-12);
  EXPECT_NEAR(fallen[2], -2.0, 1e-12);
  config.max_drift_ratio = -1.0;  // off
  config.max_heading_change_deg = -1.0;
  config.max_turn_translation_m = -1.0;
  EXPECT_EQ(omni_constraints(s, config), (std::array<double, 3>{0, 0, 0}));
}

TEST(DirectionSpeeds, BestPerDirectionAndTheTables) {
  DirectionSpeeds a, b;
  a.label = "Ind_O";
  a.speed = {0.1, 0.0, 0.01, 0.01, 0.1, 0.2};
  a.trials = 3;
  b.label = "knee";
  b.file = "front/002.json";
  b.speed = {0.05, 0.1, 0.02, 0.0, 0.3, 0.1};
  b.trials = 3;
  b.falls = 1;
  const DirectionSpeeds best = best_per_direction({a, b}, "best");
  EXPECT_EQ(best.speed, (std::array<double, kOmniSegments>{0.1, 0.1, 0.02, 0.01, 0.3, 0.2}));
  EXPECT_EQ(best.source[0], "Ind_O");
  EXPECT_EQ(best.source[1], "front/002.json");
  const DirectionSpeeds ref = reference_direction_speeds();
  EXPECT_EQ(ref.speed, (std::array<double, kOmniSegments>{0.38, 0.42, 0.26, 0.26, 1.97, 1.97}));
  const std::string text = direction_table_text({a, b, best, ref});
  EXPECT_NE(text.find("knee"), std::string::npos);
  EXPECT_NE(text.find("1/3"), std::string::npos);
  EXPECT_NE(text.find("1.970"), std::string::npos);
  const nlohmann::json j = direction_table_json({a, b, best, ref});
  ASSERT_EQ(j.size(), 4u);
  EXPECT_DOUBLE_EQ(j[1]["speeds"]["backward"].get<double>(), 0.1);
  EXPECT_EQ(j[1]["file"], "front/002.json");
  EXPECT_EQ(j[2]["source"]["turn_left"], "front/002.json");
  EXPECT_FALSE(j[3].contains("trials"));
}

}  // namespace
}  // namespace stride::opt
