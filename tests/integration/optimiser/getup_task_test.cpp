// The get-up task (issue 31 point 4, issue 43 point 3): the task scores what the episodes
// measured, a robot that stays down is infeasible, and the task is one entry of the registry.
// Its start genome is the direct get-ups the getup run started from
// (optimiser/configs/getup-start/, written by getup_keyframe_search.py): they stand up on every
// ground on both engines.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "seeds.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/optimiser/tasks/getup_figures.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "task_figures_of.hpp"

namespace stride::opt {
namespace {

const std::string kConfigs = std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/";

TaskConfig getup_config() {
  TaskConfig c;
  const Status s = load_task_config(kConfigs + "getup.json", c);
  EXPECT_TRUE(s) << s.message();
  return c;
}

EpisodeScore nominal_episodes(TaskConfig config, const std::string& contact) {
  config.world.contact = contact;
  config.trials = 1;  // the nominal world (a resampling run's single trial is randomised)
  config.settings.resample = false;
  const RobotTask task(config);
  EpisodeScore score;
  const Status s = task.run_trial(task.start_genome(), 0, score);
  EXPECT_TRUE(s) << s.message();
  const GetUpFigures f = figures_of<GetUpFigures>(score);
  std::printf(
      "%s: stood %d of 2, %d get-up attempts, stand time %.3f s, peak servo load %.2f N m, peak "
      "|a| %.2f m/s^2\n",
      contact.c_str(), f.stood, f.get_up_attempts, f.stand_time_s, score.objectives[1],
      score.max_accel);
  return score;
}

// The start genome, the direct get-ups of getup-start/ (issue 43), stands up from both sides in
// the nominal world of each ground on both engines: 8 worlds, counted with one to spare, the
// median of their stand times (the mean of the two sides) under 3 s from lying still. The
// exception is MuJoCo's seed grass, where the back stood at the fourth attempt (mean of the
// sides 4.665 s, which this test pinned to 1e-9 s with the attempts; sim_getup_cli_test.cpp says
// why). The score is the episodes' own figures: Obj1 the stand time, Obj2 the peak servo load
// (the mean of the two episodes' peak motor torques), the constraint 0 when both stood.
// Measured 2026-11-28 (the 8 worlds): 7 of 8 under 3 s, median 2.38 s (IQR 0.05, 2.30-4.67:
// MuJoCo's seed grass 4.665 s), peak servo load median 21.0 N m (IQR 3.7, 16.3-23.3).
TEST(GetUpTask, TheStartGenomeStandsUpOnEveryGroundOnBothEngines) {
  std::vector<double> times, loads;
  int stood = 0;
  for (const sim::EngineKind engine : {sim::EngineKind::kSimbody, sim::EngineKind::kMujoco}) {
    for (const char* contact : {"turf", "seed", "soft", "hard"}) {
      SCOPED_TRACE(std::string(sim::to_string(engine)) + " " + contact);
      TaskConfig config = getup_config();
      config.engines = {engine};
      const EpisodeScore s = nominal_episodes(config, contact);
      const GetUpFigures f = figures_of<GetUpFigures>(s);
      if (f.stood == 2) {
        EXPECT_DOUBLE_EQ(s.objectives[0], f.stand_time_s);
      }
      ASSERT_EQ(s.constraints.size(), 1u);
      EXPECT_EQ(s.constraints[0] == 0.0, f.stood == 2);
      stood += f.stood == 2 ? 1 : 0;
      times.push_back(f.stood == 2 ? f.stand_time_s : 1e9);
      loads.push_back(s.objectives[1]);
    }
  }
  const test::Figures time("stand time [s]", {}, times), load("peak servo load [N m]", {}, loads);
  std::printf("  %s\n  %s\n", time.summary().c_str(), load.summary().c_str());
  EXPECT_GE(stood, static_cast<int>(times.size()) - 1);
  EXPECT_GT(time.median(), 2.0);
  EXPECT_LT(time.median(), 3.0);  // 2.38 s, IQR 0.05
  // Above the MX-106's stall torque (8.4 N m at 12 V), where a limb is back-driven, and below
  // what the identified servo law allows a back-driven gear train.
  EXPECT_GT(load.median(), 8.4);  // 21.0 N m, IQR 3.7
  EXPECT_LT(load.median(), 40.0);
}

// A robot that stays down (here the get-up switched off, motion.get_up 0, under the genome) is
// infeasible, counts the time limit plus the penalty, and runs both episodes to their end.
TEST(GetUpTask, ARobotThatStaysDownIsInfeasible) {
  TaskConfig config = getup_config();
  config.base_params = {{"motion.get_up", 0.0}};
  config.duration_s = 5.0;
  const EpisodeScore s = nominal_episodes(config, "turf");
  const GetUpFigures f = figures_of<GetUpFigures>(s);
  EXPECT_EQ(f.stood, 0);
  EXPECT_EQ(f.get_up_attempts, 0);
  EXPECT_EQ(f.stand_time_s, -1.0);
  EXPECT_DOUBLE_EQ(s.objectives[0], config.duration_s + 10.0);
  EXPECT_EQ(s.constraints[0], -1.0);
  EXPECT_TRUE(s.fell);
  // Never standing, both episodes run their whole duration.
  EXPECT_NEAR(s.sim_time_s, 2.0 * config.duration_s, 0.011);
}

/// The genome of the firmware's defaults: what its get-up scripts hold without a parameter file.
Genome genome_of_the_firmware_defaults(const TaskConfig& config) {
  std::unique_ptr<fw::Firmware> firmware;
  const Status s = fw::Firmware::create({}, firmware);
  EXPECT_TRUE(s) << s.message();
  Genome g;
  if (!firmware) return g;
  for (const TaskGene& gene : config.genes) {
    const auto handle = firmware->params().find(gene.parameter);
    EXPECT_TRUE(handle.has_value()) << gene.parameter;
    g.reals.push_back(handle ? firmware->params().spec(*handle).default_value : 0.0);
  }
  return g;
}

// The firmware's default get-up is the run's start genome, the direct get-ups (the issue-43 getup
// run's picks held in fewer validation worlds than their start, optimiser/RESULTS.md): the
// scripts hold getup-start/'s values exactly. On both engines each episode of the nominal world
// ends once the robot has stood for 1 s (StoodUpWatch); whether it stands is the test above's.
TEST(GetUpTask, TheDefaultScriptsAreTheStartGenomeAndStopOnceStood) {
  TaskConfig config = getup_config();
  const Genome defaults = genome_of_the_firmware_defaults(config);
  const Genome start = RobotTask(config).start_genome();
  ASSERT_EQ(defaults.reals.size(), start.reals.size());
  for (std::size_t i = 0; i < start.reals.size(); ++i)
    EXPECT_EQ(defaults.reals[i], start.reals[i]) << config.genes[i].parameter;
  int stood = 0;
  for (const sim::EngineKind engine : {sim::EngineKind::kSimbody, sim::EngineKind::kMujoco}) {
    config.engines = {engine};
    config.trials = 1;  // the nominal world (a resampling run's single trial is randomised)
    config.settings.resample = false;
    const RobotTask task(config);
    EpisodeScore by_default;
    ASSERT_TRUE(task.run_trial(defaults, 0, by_default));
    const GetUpFigures d = figures_of<GetUpFigures>(by_default);
    std::printf("%s: the defaults stood %d of 2 in %.2f s, peak servo load %.2f N m\n",
                sim::to_string(engine), d.stood, d.stand_time_s, by_default.objectives[1]);
    if (d.stood != 2) continue;
    ++stood;
    EXPECT_GT(by_default.sim_time_s, 2.0 * (d.stand_time_s + 1.0) - 0.011);
    EXPECT_LT(by_default.sim_time_s, 2.0 * (d.stand_time_s + 1.5)) << sim::to_string(engine);
  }
  EXPECT_GE(stood, 1);
}

TEST(GetUpTask, IsOneEntryOfTheRegistryAndAnUnknownTaskNamesTheChoices) {
  const TaskType* type = find_task_type("getup");
  ASSERT_NE(type, nullptr);
  EXPECT_EQ(type->descriptor().episodes_per_world, 2);
  EXPECT_EQ(type->descriptor().constraint_count, 1);
  const TaskConfig config = getup_config();
  EXPECT_EQ(RobotTask(config).shape().constraints, 1);
  EXPECT_EQ(config.genes.size(), 116u);  // 108 targets and 8 frame durations
  nlohmann::json doc;
  std::ifstream(kConfigs + "getup.json") >> doc;
  doc["task"] = "getdown";
  TaskConfig bad;
  const Status s = parse_task_config(doc, bad);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(),
            "task: 'getdown' is not walk, walk-omni, walk-ramp, walk-command, kick or getup");
}

}  // namespace
}  // namespace stride::opt
