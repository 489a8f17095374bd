// The speed-ramp walk task (issue 32 point 1): Ind_O's top speed per direction in the nominal
// faithful world, the objective as the Bit-Bots' combination of them, the direction table the
// report and validation show, and a bad ramp setting named.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "stride/optimiser/tasks/robot_task.hpp"

namespace stride::opt {
namespace {

const std::string kConfigs = std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/";

TEST(WalkRampTask, IndOsTopSpeedPerDirectionMakeItsScore) {
  TaskConfig config;
  ASSERT_TRUE(load_task_config(kConfigs + "walk-ramp.json", config));
  config.trials = 1;  // the nominal world
  const RobotTask task(config);
  ASSERT_TRUE(task.check());
  EXPECT_EQ(task.type()->episodes_per_world(), 6);
  EpisodeScore s;
  ASSERT_TRUE(task.run_trial(task.start_genome(), 0, s));
  double score = 0.0;
  const double weights[] = {1.0, 1.0, 1.0, 1.0, 0.1, 0.1};
  for (int d = 0; d < kOmniSegments; ++d) {
    const OmniSegment& seg = s.omni[static_cast<std::size_t>(d)];
    std::printf("%-10s measured %d, top speed %.4f, drift %.3f, heading %.3f, translation %.3f\n",
                to_string(static_cast<OmniDirection>(d)), seg.measured, seg.speed, seg.drift_ratio,
                seg.heading_change_rad, seg.translation_m);
    EXPECT_GE(seg.speed, 0.0);
    if (!seg.measured) {
      EXPECT_EQ(seg.speed, 0.0);
    }
    score += weights[d] * seg.speed;
  }
  std::printf("objectives %.5f %.3f, constraints %.3f %.3f\n", s.objectives[0], s.objectives[1],
              s.constraints[0], s.constraints[1]);
  // Forward: the faithful walk holds a speed (Ind_O walks 2.5 m in 19.1 s).
  EXPECT_TRUE(s.omni[0].measured);
  EXPECT_GT(s.omni[0].speed, 0.08);
  EXPECT_NEAR(s.objectives[0], -score, 1e-9);
  EXPECT_GT(s.objectives[1], 9.81);
  ASSERT_EQ(s.constraints.size(), 2u);
  for (const double c : s.constraints) EXPECT_LE(c, 0.0);
  // The same genome, the same figures (deterministic).
  EpisodeScore again;
  ASSERT_TRUE(task.run_trial(task.start_genome(), 0, again));
  EXPECT_EQ(again.objectives, s.objectives);
}

TEST(WalkRampTask, ABadRampSettingIsNamed) {
  nlohmann::json doc;
  std::ifstream(kConfigs + "walk-ramp.json") >> doc;
  TaskConfig c;
  doc["ramp"]["measure_s"] = 5.0;  // longer than hold_s
  Status s = parse_task_config(doc, c);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(), "ramp.measure_s: must be in (0, hold_s]");
  doc["ramp"] = {{"speed", 1}};
  s = parse_task_config(doc, c);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(),
            "ramp.speed: unknown field (known: start_s, increment, hold_s, measure_s, max_levels, "
            "patience)");
}

}  // namespace
}  // namespace stride::opt
