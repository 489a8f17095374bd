// The get-up task (issue 31 point 4): the stock get-up scripts stand the robot up from lying on
// its front and on its back in the faithful world, the task scores what the episodes measured,
// a get-up script that cannot work is infeasible, and the task is one entry of the registry.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "stride/optimiser/tasks/robot_task.hpp"

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
  config.trials = 1;  // the nominal world
  const RobotTask task(config);
  EpisodeScore score;
  const Status s = task.run_trial(task.start_genome(), 0, score);
  EXPECT_TRUE(s) << s.message();
  std::printf("%s: stood %d of 2, %d get-up attempts, stand time %.3f s, peak |a| %.2f m/s^2\n",
              contact.c_str(), score.stood, score.get_up_attempts, score.stand_time_s,
              score.max_accel);
  return score;
}

TEST(GetUpTask, TheStockScriptsStandUpOnTheSeedsGrass) {
  TaskConfig config = getup_config();
  config.duration_s = 40.0;  // the front roll may need a retry
  const EpisodeScore s = nominal_episodes(config, "seed");
  EXPECT_EQ(s.stood, 2);
  EXPECT_NEAR(s.stand_time_s, 14.315, 0.05);  // deterministic: front and back, mean
  EXPECT_DOUBLE_EQ(s.objectives[0], s.stand_time_s);
  // Obj2 is the mean of the two episodes' peaks; max_accel the larger peak.
  EXPECT_GT(s.objectives[1], 9.81);
  EXPECT_LE(s.objectives[1], s.max_accel);
  ASSERT_EQ(s.constraints.size(), 1u);
  EXPECT_EQ(s.constraints[0], 0.0);
  EXPECT_FALSE(s.fell);
}

// The scripts were authored on the seed's 2 cm grass; on the faithful world's turf (a 5 mm layer
// over solid ground) neither stands the robot up, which is what the getup run is for.
TEST(GetUpTask, OnTurfTheStockScriptsDoNotStandAndTheGenomeIsInfeasible) {
  const TaskConfig config = getup_config();
  const EpisodeScore s = nominal_episodes(config, "turf");
  EXPECT_EQ(s.stood, 0);
  EXPECT_GE(s.get_up_attempts, 4);  // it keeps trying
  EXPECT_EQ(s.stand_time_s, -1.0);
  EXPECT_DOUBLE_EQ(s.objectives[0], config.duration_s + 10.0);
  EXPECT_EQ(s.constraints[0], -1.0);
  EXPECT_TRUE(s.fell);
}

/// The genome of a parameter file (the config's genes, in order).
Genome genome_from_file(const TaskConfig& config, const std::string& file) {
  nlohmann::json doc;
  std::ifstream(file) >> doc;
  Genome g;
  for (const TaskGene& gene : config.genes) g.reals.push_back(doc.at(gene.parameter).get<double>());
  return g;
}

// The shipped pick (firmware/config/get-up-turf.json, the getup run's knee): it stands up from
// both sides on the faithful world's turf, where the stock scripts stay down, on both engines.
TEST(GetUpTask, TheShippedPickStandsUpOnTurfOnBothEngines) {
  TaskConfig config = getup_config();
  const Genome pick = genome_from_file(
      config, std::string(STRIDE_SOURCE_DIR) + "/firmware/config/get-up-turf.json");
  for (const sim::EngineKind engine : {sim::EngineKind::kSimbody, sim::EngineKind::kMujoco}) {
    config.engines = {engine};
    config.trials = 1;  // the nominal world
    const RobotTask task(config);
    EpisodeScore stock, picked;
    ASSERT_TRUE(task.run_trial(task.start_genome(), 0, stock));
    ASSERT_TRUE(task.run_trial(pick, 0, picked));
    std::printf("%s: stock stood %d of 2 (%.2f s), the pick %d of 2 in %.2f s, peak |a| %.1f\n",
                sim::to_string(engine), stock.stood, stock.stand_time_s, picked.stood,
                picked.stand_time_s, picked.objectives[1]);
    EXPECT_EQ(picked.stood, 2) << sim::to_string(engine);
    EXPECT_GT(picked.stand_time_s, 0.0);
    EXPECT_LT(picked.stand_time_s, 12.0) << sim::to_string(engine);
    if (engine == sim::EngineKind::kSimbody) {
      EXPECT_EQ(stock.stood, 0);
    }
  }
}

TEST(GetUpTask, IsOneEntryOfTheRegistryAndAnUnknownTaskNamesTheChoices) {
  const TaskType* type = find_task_type("getup");
  ASSERT_NE(type, nullptr);
  EXPECT_EQ(type->episodes_per_world(), 2);
  EXPECT_EQ(type->constraint_count(), 1);
  const TaskConfig config = getup_config();
  EXPECT_EQ(RobotTask(config).shape().constraints, 1);
  EXPECT_EQ(config.genes.size(), 213u);  // 198 targets and 15 frame durations
  nlohmann::json doc;
  std::ifstream(kConfigs + "getup.json") >> doc;
  doc["task"] = "getdown";
  TaskConfig bad;
  const Status s = parse_task_config(doc, bad);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(), "task: 'getdown' is not walk, walk-omni, walk-ramp, kick or getup");
}

}  // namespace
}  // namespace stride::opt
