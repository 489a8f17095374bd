// The trials' physics step per engine (TaskType::trial_physics_step_us): a run whose trials
// include MuJoCo steps at the 2 ms that engine allows, a Simbody run at 2.5 ms, the get-up at
// 2 ms, a step the config gives is kept, and a change of engines after parsing (stride optimise
// --engine) moves only a default step. Figures: tests/bench/RESULTS.md, "The step the model
// allows".
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "minimal_task_config.hpp"
#include "stride/optimiser/tasks/task_config.hpp"

namespace stride::opt {
namespace {

nlohmann::json walk_config() {
  return minimal_task_config();
}

std::int64_t step_of(const nlohmann::json& doc) {
  TaskConfig c;
  const Status s = parse_task_config(doc, c);
  EXPECT_TRUE(s) << s.message();
  return c.world.physics_step_us;
}

TEST(TrialStep, EachEngineSetsTheDefaultAndAGivenStepIsKept) {
  EXPECT_EQ(step_of(walk_config()), 2500);  // Simbody
  auto d = walk_config();
  d["engines"] = {"mujoco"};
  EXPECT_EQ(step_of(d), 2000);
  d["engines"] = {"simbody", "mujoco"};
  EXPECT_EQ(step_of(d), 2000);  // one step for every trial of a run: the smaller
  d["physics_step_us"] = 2500;
  EXPECT_EQ(step_of(d), 2500);  // given: kept
  d = walk_config();
  d["task"] = "getup";
  EXPECT_EQ(step_of(d), 2000);
  d = walk_config();
  d["world"] = "seed";
  d["engines"] = {"simbody"};
  EXPECT_EQ(step_of(d), 2000);  // the seed's world keeps the table's default
}

TEST(TrialStep, ChangingTheEnginesMovesOnlyADefaultStep) {
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(walk_config(), c));
  EXPECT_TRUE(c.trial_step_from_task);
  c.engines = {sim::EngineKind::kSimbody, sim::EngineKind::kMujoco};
  apply_task_trial_step(c);
  EXPECT_EQ(c.world.physics_step_us, 2000);
  auto given = walk_config();
  given["physics_step_us"] = 2500;
  ASSERT_TRUE(parse_task_config(given, c));
  EXPECT_FALSE(c.trial_step_from_task);
  c.engines = {sim::EngineKind::kMujoco};
  apply_task_trial_step(c);
  EXPECT_EQ(c.world.physics_step_us, 2500);
}

}  // namespace
}  // namespace stride::opt
