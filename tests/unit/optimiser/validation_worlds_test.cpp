// The validation worlds as WorldSpecs (issue 44 point 2): each world's episodes run in exactly
// the options the worlds had when validation_worlds edited WorldOptions directly (the mapping
// before the change, transcribed below as the reference), for run configs with the faithful
// and the seed world, randomised trials, a world friction, a ball and explicit --engine and
// --physics-step-us; and validation.json writes each world's options with the world option
// table's keys, which read back into the same world.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "minimal_task_config.hpp"
#include "same_world.hpp"
#include "stride/optimiser/run/validation.hpp"
#include "stride/optimiser/run/validation_summary.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::opt {
namespace {

struct OldWorld {
  std::string name;
  sim::WorldOptions options;
};

// validation_worlds as it was (commit 838df13): the run's first trial world's options with
// IMU noise on, edited per world.
std::vector<OldWorld> old_validation_worlds(const RobotTask& task,
                                            const ValidationOptions& options) {
  const TaskConfig& config = task.config();
  sim::WorldOptions base = task.world_options(0);
  base.imu.set_noise(true);
  const std::int64_t step_ns =
      options.physics_step_ns > 0 ? options.physics_step_ns : base.physics_step_ns / 2;
  std::vector<sim::EngineKind> engines = options.engines;
  if (engines.empty())
    for (sim::EngineKind e : {sim::EngineKind::kSimbody, sim::EngineKind::kMujoco})
      if (std::find(config.engines.begin(), config.engines.end(), e) == config.engines.end())
        engines.push_back(e);
  const TaskType* type = find_task_type(config.task);
  std::vector<OldWorld> out;
  for (sim::EngineKind e : engines) {
    OldWorld w{std::string("engine ") + sim::to_string(e), base};
    w.options.engine = e;
    w.options.physics_step_ns =
        std::min(w.options.physics_step_ns, type->descriptor().trial_physics_step_us(e) * 1000);
    out.push_back(w);
  }
  out.push_back({"fresh seeds", base});
  OldWorld wider{"wider randomisation", base};
  sim::Randomisation& r = wider.options.randomise;
  auto widen = [](double run, double floor) { return std::min(0.9, std::max(1.5 * run, floor)); };
  r.friction_range = widen(r.friction_range, 1.5 * TrialRandomisation{}.friction_range);
  r.mass_range = widen(r.mass_range, 1.5 * TrialRandomisation{}.mass_range);
  r.strength_range = widen(r.strength_range, 1.5 * TrialRandomisation{}.strength_range);
  r.contact_range = widen(r.contact_range, 0.0);
  r.com_range = std::min(0.05, 1.5 * r.com_range);
  r.latency_probability = std::max(0.5, r.latency_probability);
  out.push_back(wider);
  // Added by issue 54 (not in 838df13): the servos and the supply drawn off the model.
  OldWorld servos{"servos off the model", base};
  sim::Randomisation& o = servos.options.randomise;
  o.servo_friction_min = 0.8;
  o.servo_friction_max = 1.6;
  o.servo_torque_min = 0.8;
  o.servo_torque_max = 1.05;
  o.supply_min_v = 12.0;
  o.supply_max_v = 16.8;
  o.latency_probability = std::max(0.5, o.latency_probability);
  out.push_back(servos);
  OldWorld half{options.physics_step_ns > 0 ? "step " + std::to_string(step_ns / 1000) + " us"
                                            : std::string("half step"),
                base};
  half.options.physics_step_ns = step_ns;
  out.push_back(half);
  for (const char* ground : {"soft", "hard"}) {
    OldWorld w{std::string("ground ") + ground, base};
    const double friction = w.options.contact.friction;
    sim::parse_contact_kind(ground, w.options.contact);
    w.options.contact.friction = friction;
    w.options.randomise.contact_range = 0.0;
    out.push_back(w);
  }
  return out;
}

// The worlds of `config` with `options` against the old mapping, every seed of every world.
void expect_old_worlds(const nlohmann::json& config, const ValidationOptions& options) {
  SCOPED_TRACE(config.dump());
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(config, c));
  const RobotTask task(c);
  std::vector<ValidationWorld> worlds;
  ASSERT_TRUE(validation_worlds(task, options, worlds));
  const std::vector<OldWorld> old = old_validation_worlds(task, options);
  ASSERT_EQ(worlds.size(), old.size());
  for (std::size_t w = 0; w < worlds.size(); ++w) {
    EXPECT_EQ(worlds[w].name, old[w].name);
    ASSERT_EQ(worlds[w].seeds.size(), static_cast<std::size_t>(options.seeds));
    for (std::size_t s = 0; s < worlds[w].seeds.size(); ++s) {
      EXPECT_EQ(worlds[w].seeds[s], c.trial_seed + kValidationSeedOffset + s);
      sim::WorldOptions expected = old[w].options;
      expected.seed = worlds[w].seeds[s];
      expect_same_world(validation_episode_world(task, worlds[w], s), expected,
                        worlds[w].name + ", seed " + std::to_string(s));
    }
  }
}

// A run whose trials draw the servos already (getup.json) is not validated twice in that world.
TEST(ValidationWorlds, ARunThatDrawsTheServosHasNoSeparateServoWorld) {
  auto names = [](const nlohmann::json& config) {
    TaskConfig c;
    EXPECT_TRUE(parse_task_config(config, c));
    std::vector<ValidationWorld> worlds;
    EXPECT_TRUE(validation_worlds(RobotTask(c), ValidationOptions{}, worlds));
    std::vector<std::string> out;
    for (const ValidationWorld& w : worlds) out.push_back(w.name);
    return out;
  };
  const auto has_servo_world = [](const std::vector<std::string>& n) {
    return std::find(n.begin(), n.end(), "servos off the model") != n.end();
  };
  nlohmann::json plain = minimal_task_config();
  plain["trials"] = 2;
  EXPECT_TRUE(has_servo_world(names(plain)));
  nlohmann::json drawing = plain;
  drawing["randomisation"] = {{"supply_min", 12.0}, {"supply_max", 16.8}};
  const std::vector<std::string> without = names(drawing);
  EXPECT_FALSE(has_servo_world(without));
  EXPECT_EQ(without.size() + 1, names(plain).size());
}

TEST(ValidationWorlds, EachWorldRunsTheOptionsTheOldMappingGave) {
  ValidationOptions options;
  options.seeds = 3;
  // The faithful world (turf), one nominal trial, Simbody.
  expect_old_worlds(minimal_task_config(), options);
  // Randomised trials with a ground and a robot range, the seed's world with its own friction
  // and a 2.5 ms step on Simbody (2 ms on MuJoCo), trial seed 7.
  nlohmann::json robust = minimal_task_config();
  robust["trials"] = 3;
  robust["trial_seed"] = 7;
  robust["randomisation"] = {{"imu_noise", false},   {"friction_range", 0.3},
                             {"mass_range", 0.1},    {"strength_range", 0.05},
                             {"contact_range", 0.4}, {"com_range", 0.01}};
  robust["world"] = {{"base", "seed"}, {"friction", 0.8}, {"physics_step_us", 2500}};
  expect_old_worlds(robust, options);
  // A kick (the ball stays) on MuJoCo, the hard ground, validated on both engines and a 1 ms
  // step.
  nlohmann::json kick = minimal_task_config();
  kick["task"] = "kick";
  kick["engines"] = {"mujoco"};
  kick["world"] = {{"contact", "hard"}};
  options.engines = {sim::EngineKind::kSimbody, sim::EngineKind::kMujoco};
  options.physics_step_ns = 1'000'000;
  expect_old_worlds(kick, options);
}

TEST(ValidationWorlds, HalfAStepThatIsNoWholeMicrosecondIsAnErrorNamingTheOption) {
  nlohmann::json config = minimal_task_config();
  config["world"] = {{"physics_step_us", 125}};  // divides 10 ms; its half, 62.5 us, does not
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(config, c));
  std::vector<ValidationWorld> worlds;
  const Status s = validation_worlds(RobotTask(c), ValidationOptions{}, worlds);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message().rfind("--physics-step-us: half the run's step (125 us)", 0), 0u)
      << s.message();
  EXPECT_TRUE(worlds.empty());
  ValidationOptions options;
  options.physics_step_ns = 100'000;  // given: fine
  EXPECT_TRUE(validation_worlds(RobotTask(c), options, worlds));
}

TEST(ValidationWorlds, TheFileWritesEachWorldWithTheTablesKeysAndReadsItBack) {
  nlohmann::json config = minimal_task_config();
  config["trials"] = 2;
  config["world"] = {{"contact", "seed"}, {"friction", 0.9}};
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(config, c));
  const RobotTask task(c);
  ValidationOptions options;
  options.seeds = 2;
  std::vector<ValidationWorld> worlds;
  ASSERT_TRUE(validation_worlds(task, options, worlds));
  std::vector<ValidationIndividual> individuals(1);
  individuals[0].name = "Ind_O";
  individuals[0].run_objectives = {20.0, 20.0};
  EpisodeOutcome not_run;  // the scores do not matter here
  not_run.setup_error = "not run";
  std::vector<std::vector<std::vector<EpisodeOutcome>>> outcomes(
      1, std::vector<std::vector<EpisodeOutcome>>(worlds.size(), {not_run, not_run}));
  const nlohmann::json doc = summarise_validation("run", c, individuals, worlds, outcomes);
  EXPECT_EQ(doc["format"], "stride-validation-2");
  EXPECT_TRUE(is_validation_file(doc));
  ASSERT_EQ(doc["worlds"].size(), worlds.size());
  for (std::size_t w = 0; w < worlds.size(); ++w) {
    const nlohmann::json& entry = doc["worlds"][w];
    SCOPED_TRACE(entry.dump());
    EXPECT_EQ(entry["name"], worlds[w].name);
    EXPECT_EQ(entry["seeds"], nlohmann::json(worlds[w].seeds));
    ASSERT_TRUE(entry["world"].is_object());
    for (const auto& [key, value] : entry["world"].items())
      EXPECT_NE(sim::find_world_option(key), nullptr) << key << " is not a world option";
    EXPECT_FALSE(entry.contains("imu_noise"));
    EXPECT_NE(entry["world"].value("noise", "on"), "off");  // on: the default, not written
    EXPECT_EQ(entry["world"]["seed"], worlds[w].seeds.front());
    // The record is the world: read back, it runs the first seed's options.
    sim::WorldSpec back;
    ASSERT_TRUE(sim::read_world_spec(entry["world"], "world.", back));
    expect_same_world(task.world_options(back), validation_episode_world(task, worlds[w], 0),
                      worlds[w].name);
  }
  // What the tables show of a world: the ground's name and the figures, from the record.
  // Worlds: engine mujoco, fresh seeds, wider randomisation, servos off the model, half step,
  // ground soft, hard.
  ASSERT_EQ(worlds.size(), 7u);
  const nlohmann::json engine = validation_world_columns(doc["worlds"][0]);
  EXPECT_EQ(engine["engine"], "mujoco");
  EXPECT_EQ(engine["contact"], "seed");  // the run's ground (with its friction 0.9)
  const nlohmann::json wider = validation_world_columns(doc["worlds"][2]);
  EXPECT_EQ(wider["engine"], "simbody");
  EXPECT_DOUBLE_EQ(wider["latency_probability"].get<double>(), 0.5);
  const nlohmann::json servos = validation_world_columns(doc["worlds"][3]);
  EXPECT_DOUBLE_EQ(servos["servo_friction_max"].get<double>(), 1.6);
  EXPECT_DOUBLE_EQ(servos["supply_min"].get<double>(), 12.0);
  // Half the walk's 2.5 ms trial step.
  EXPECT_EQ(validation_world_columns(doc["worlds"][4])["physics_step_us"], 1250);
  EXPECT_EQ(validation_world_columns(doc["worlds"][5])["contact"], "soft");
  EXPECT_EQ(validation_world_columns(doc["worlds"][6])["contact"], "hard");
  EXPECT_EQ(doc["worlds"][6]["unavailable"], "not run");
}

TEST(ValidationWorlds, TheTablesReadTheWorldsOfAStrideValidation1File) {
  const nlohmann::json old = {{"name", "ground soft"},   {"engine", "simbody"},
                              {"physics_step_us", 2000}, {"imu_noise", true},
                              {"contact", "soft"},       {"friction_range", 0.2},
                              {"seeds", {1001, 1002}}};
  EXPECT_TRUE(is_validation_file({{"format", "stride-validation-1"}}));
  EXPECT_FALSE(is_validation_file({{"format", "stride-validation-9"}}));
  const nlohmann::json columns = validation_world_columns(old);
  EXPECT_EQ(columns["contact"], "soft");
  EXPECT_EQ(columns["physics_step_us"], 2000);
  EXPECT_DOUBLE_EQ(columns["friction_range"].get<double>(), 0.2);
}

}  // namespace
}  // namespace stride::opt
