// The get-up task (issue 31 point 4, issue 43 point 3): the task scores what the episodes
// measured, a robot that stays down is infeasible, and the task is one entry of the registry.
// Its start genome is the direct get-ups the getup run started from
// (optimiser/configs/getup-start/, written by getup_keyframe_search.py): they stand up on every
// ground on both engines.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

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

// The start genome, the direct get-ups of getup-start/ (issue 43), stands up from both sides
// on every ground on both engines in the nominal world, at the first try in under 3 s from lying
// still (the mean of the two sides), except from the back on MuJoCo's seed grass: there it stands
// at the fourth attempt (the mean of the sides 4.665 s; sim_getup_cli_test.cpp says why).
TEST(GetUpTask, TheStartGenomeStandsUpOnEveryGroundOnBothEngines) {
  for (const sim::EngineKind engine : {sim::EngineKind::kSimbody, sim::EngineKind::kMujoco}) {
    for (const char* contact : {"turf", "seed", "soft", "hard"}) {
      TaskConfig config = getup_config();
      config.engines = {engine};
      const EpisodeScore s = nominal_episodes(config, contact);
      const GetUpFigures f = figures_of<GetUpFigures>(s);
      const bool exception = engine == sim::EngineKind::kMujoco && std::string(contact) == "seed";
      EXPECT_EQ(f.stood, 2) << sim::to_string(engine) << " " << contact;
      EXPECT_EQ(f.get_up_attempts, exception ? 4 : 2) << sim::to_string(engine) << " " << contact;
      EXPECT_GT(f.stand_time_s, 2.0) << sim::to_string(engine) << " " << contact;
      if (exception)
        EXPECT_NEAR(f.stand_time_s, 4.665, 1e-9);
      else
        EXPECT_LT(f.stand_time_s, 3.0) << sim::to_string(engine) << " " << contact;
      EXPECT_DOUBLE_EQ(s.objectives[0], f.stand_time_s);
      // Obj2, the peak servo load, is the mean of the two episodes' peak motor torques: above
      // the MX-106's stall torque (8.4 N m at 12 V), where a limb is back-driven, and below
      // what the identified servo law allows a back-driven gear train.
      EXPECT_GT(s.objectives[1], 8.4) << sim::to_string(engine) << " " << contact;
      EXPECT_LT(s.objectives[1], 40.0) << sim::to_string(engine) << " " << contact;
      ASSERT_EQ(s.constraints.size(), 1u);
      EXPECT_EQ(s.constraints[0], 0.0);
      EXPECT_FALSE(s.fell);
    }
  }
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
// scripts hold getup-start/'s values exactly. On both engines it stands up from both sides in
// the nominal world, and each episode ends once the robot has stood for 1 s (StoodUpWatch).
TEST(GetUpTask, TheDefaultScriptsAreTheStartGenomeAndStandUpOnBothEngines) {
  TaskConfig config = getup_config();
  const Genome defaults = genome_of_the_firmware_defaults(config);
  const Genome start = RobotTask(config).start_genome();
  ASSERT_EQ(defaults.reals.size(), start.reals.size());
  for (std::size_t i = 0; i < start.reals.size(); ++i)
    EXPECT_EQ(defaults.reals[i], start.reals[i]) << config.genes[i].parameter;
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
    EXPECT_EQ(d.stood, 2) << sim::to_string(engine);
    EXPECT_GT(d.stand_time_s, 2.0);
    EXPECT_LT(d.stand_time_s, 3.0) << sim::to_string(engine);
    EXPECT_GT(by_default.sim_time_s, 2.0 * (d.stand_time_s + 1.0) - 0.011);
    EXPECT_LT(by_default.sim_time_s, 2.0 * (d.stand_time_s + 1.5)) << sim::to_string(engine);
  }
}

TEST(GetUpTask, IsOneEntryOfTheRegistryAndAnUnknownTaskNamesTheChoices) {
  const TaskType* type = find_task_type("getup");
  ASSERT_NE(type, nullptr);
  EXPECT_EQ(type->episodes_per_world(), 2);
  EXPECT_EQ(type->constraint_count(), 1);
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
