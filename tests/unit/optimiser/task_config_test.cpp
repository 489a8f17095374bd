// Task configs: the shipped configs carry the seed's settings; errors name the field; report
// helpers (non-dominated filter, knee point) and the progress line.
#include <gtest/gtest.h>

#include "minimal_task_config.hpp"
#include "stride/optimiser/run/progress.hpp"
#include "stride/optimiser/run/run_report.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
#include "stride/optimiser/tasks/walk_omni_settings.hpp"
#include "stride/optimiser/tasks/walk_settings.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

const std::string kConfigs = std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/";

TEST(TaskConfig, WalkConfigIsTheSeedsTable71With46Genes) {
  TaskConfig c;
  ASSERT_TRUE(load_task_config(kConfigs + "walk.json", c)) << "walk.json";
  EXPECT_EQ(c.task, "walk");
  EXPECT_EQ(c.settings.seed, 300u);
  EXPECT_EQ(c.settings.pop_size, 40);
  EXPECT_EQ(c.settings.generations, 50);
  EXPECT_DOUBLE_EQ(c.settings.real_mut_prob, 0.025);
  EXPECT_DOUBLE_EQ(c.settings.real_cross_prob, 0.8);
  EXPECT_DOUBLE_EQ(c.settings.eta_c, 13);
  EXPECT_DOUBLE_EQ(c.settings.eta_m, 20);
  ASSERT_EQ(c.genes.size(), 46u);
  for (const auto& g : c.genes) {
    EXPECT_NE(g.parameter, "walk.stance.body_height");
    if (g.start != 0.0) {  // about +-50 % of Ind_O (less where a physical range clips it)
      const double width = std::abs(g.max - g.min) / std::abs(g.start);
      EXPECT_GE(width, 0.5) << g.parameter;
      EXPECT_LE(width, 1.35) << g.parameter;
    } else {
      EXPECT_LT(g.min, g.max) << g.parameter;  // an absolute interval
    }
  }
  const RobotTask task(c);
  EXPECT_EQ(task.shape().reals.size(), 46u);
  // fell, lateral drift, heading change (issue 22: straightness on by default).
  EXPECT_EQ(task.shape().constraints, 3);
  EXPECT_DOUBLE_EQ(c.own_settings<WalkSettings>().straightness.max_drift_ratio, 0.1);
  EXPECT_DOUBLE_EQ(c.own_settings<WalkSettings>().straightness.max_heading_change_deg, 10.0);
  EXPECT_EQ(task.start_genome().reals[0], c.genes[0].start);
}

TEST(TaskConfig, WalkOmniConfigHasTheWalkGenesWidenedAndTheBalanceGains) {
  TaskConfig omni, walk;
  ASSERT_TRUE(load_task_config(kConfigs + "walk-omni.json", omni));
  ASSERT_TRUE(load_task_config(kConfigs + "walk.json", walk));
  EXPECT_EQ(omni.task, "walk-omni");
  EXPECT_EQ(omni.trials, 3);
  EXPECT_TRUE(omni.randomisation.imu_noise);
  ASSERT_EQ(omni.genes.size(), 54u);
  int wider = 0;
  for (std::size_t i = 0; i < 46; ++i) {
    EXPECT_EQ(omni.genes[i].parameter, walk.genes[i].parameter);
    EXPECT_EQ(omni.genes[i].start, walk.genes[i].start);
    EXPECT_LE(omni.genes[i].min, walk.genes[i].min);
    EXPECT_GE(omni.genes[i].max, walk.genes[i].max);
    if (omni.genes[i].max - omni.genes[i].min > walk.genes[i].max - walk.genes[i].min) ++wider;
  }
  EXPECT_EQ(wider, 14);
  for (std::size_t i = 46; i < omni.genes.size(); ++i)
    EXPECT_EQ(omni.genes[i].parameter.rfind("walk.balance.", 0), 0u) << omni.genes[i].parameter;
  EXPECT_EQ(omni.genes.back().parameter, "walk.balance.heading_rate_gain");
  EXPECT_DOUBLE_EQ(omni.own_settings<OmniSettings>().timing.hold_s, 8.0);
  EXPECT_DOUBLE_EQ(omni.own_settings<OmniSettings>().timing.total_s(), 4.0 + 6 * 11.0);
  const RobotTask task(omni);
  EXPECT_EQ(task.shape().constraints, 4);
  EXPECT_EQ(task.shape().objectives, 2);
}

TEST(TaskConfig, KickConfigsAreTheSeedsTable61) {
  TaskConfig soft, initial;
  ASSERT_TRUE(load_task_config(kConfigs + "kick.json", soft));
  ASSERT_TRUE(load_task_config(kConfigs + "kick-initial.json", initial));
  EXPECT_EQ(soft.settings.seed, 650u);
  EXPECT_EQ(soft.settings.generations, 300);
  EXPECT_DOUBLE_EQ(soft.settings.real_mut_prob, 0.025);
  EXPECT_DOUBLE_EQ(soft.settings.real_cross_prob, 0.8);
  EXPECT_DOUBLE_EQ(soft.settings.eta_c, 15);
  EXPECT_DOUBLE_EQ(soft.settings.eta_m, 40);
  EXPECT_EQ(initial.settings.seed, 123u);
  EXPECT_EQ(initial.settings.generations, 500);
  EXPECT_DOUBLE_EQ(initial.settings.real_mut_prob, 0.2);
  EXPECT_DOUBLE_EQ(initial.settings.real_cross_prob, 0.33);
  EXPECT_DOUBLE_EQ(initial.settings.eta_c, 18);
  EXPECT_DOUBLE_EQ(initial.settings.eta_m, 50);
  // Frames 2..5 of the 6-frame kick, 18 servos each, +-0.5 rad (clipped to servo limits).
  ASSERT_EQ(soft.genes.size(), 72u);
  EXPECT_EQ(soft.genes.front().parameter.rfind("script.kick_right.frame2.", 0), 0u);
  EXPECT_EQ(soft.genes.back().parameter.rfind("script.kick_right.frame5.", 0), 0u);
  for (const auto& g : soft.genes) {
    EXPECT_LE(g.max - g.start, 0.5 + 1e-9);
    EXPECT_LE(g.start - g.min, 0.5 + 1e-9);
  }
  EXPECT_EQ(RobotTask(soft).shape().constraints, 2);
}

nlohmann::json minimal() {
  return minimal_task_config();
}

std::string error_of(const nlohmann::json& doc) {
  return parse_error_of(doc);
}

TEST(TaskConfig, ErrorsNameTheField) {
  EXPECT_EQ(error_of(minimal()), "ok");
  auto d = minimal();
  d["task"] = "swim";
  EXPECT_NE(error_of(d).find("task"), std::string::npos);
  d = minimal();
  d.erase("pop");
  EXPECT_EQ(error_of(d), "pop: missing");
  d = minimal();
  d["pc"] = "high";
  EXPECT_EQ(error_of(d), "pc: must be a number");
  d = minimal();
  d["genes"][0]["max"] = 0.1;
  EXPECT_EQ(error_of(d), "genes[0].max: must be greater than min");
  d = minimal();
  d["genes"][0]["start"] = 0.9;
  EXPECT_EQ(error_of(d), "genes[0].start: must lie within [min, max]");
  d = minimal();
  d["aggregate"] = "median";
  EXPECT_NE(error_of(d).find("aggregate"), std::string::npos);
  d = minimal();
  d["trials"] = 0;
  EXPECT_NE(error_of(d).find("trials"), std::string::npos);
  d = minimal();
  d["colour"] = 1;
  EXPECT_EQ(error_of(d), "colour: unknown field");
  d = minimal();
  d["randomisation"] = {{"friction_range", 2.0}};
  EXPECT_NE(error_of(d).find("randomisation.friction_range"), std::string::npos);
  d = minimal();
  d["max_drift_ratio"] = -0.1;
  EXPECT_EQ(error_of(d), "max_drift_ratio: must be >= 0 or null (off)");
  d = minimal();
  d["max_heading_change_deg"] = nullptr;  // off
  EXPECT_EQ(error_of(d), "ok");
  d = minimal();
  d["task"] = "walk-omni";  // its own setting: read by walk-omni, an error for walk
  d["omni"] = {{"hold_s", 0.5}};
  EXPECT_EQ(error_of(d), "omni.hold_s: must be at least 1 s");
  d["omni"] = {{"pause_s", 1.0}};
  EXPECT_EQ(error_of(d), "omni.pause_s: unknown field");
  d["omni"] = {{"start_s", "soon"}};
  EXPECT_EQ(error_of(d), "omni.start_s: must be a number");
  d["task"] = "walk";
  EXPECT_EQ(error_of(d), "field 'omni' belongs to task walk-omni, not walk");
}

TEST(TaskConfig, StraightnessLimitsRoundTripIncludingOff) {
  auto d = minimal();
  d["max_drift_ratio"] = nullptr;
  d["max_turn_translation_m"] = 0.2;
  TaskConfig a, b;
  ASSERT_TRUE(parse_task_config(d, a));
  EXPECT_LT(a.own_settings<WalkSettings>().straightness.max_drift_ratio, 0.0);
  EXPECT_DOUBLE_EQ(a.own_settings<WalkSettings>().straightness.max_heading_change_deg, 10.0);
  const nlohmann::json j = to_json(a);
  EXPECT_TRUE(j["max_drift_ratio"].is_null());
  ASSERT_TRUE(parse_task_config(j, b));
  EXPECT_LT(b.own_settings<WalkSettings>().straightness.max_drift_ratio, 0.0);
  EXPECT_DOUBLE_EQ(b.own_settings<WalkSettings>().straightness.max_turn_translation_m, 0.2);
}

// Issue 21: the engines a genome is scored on, and the validation's seed count.
TEST(TaskConfig, EnginesAndValidateSeedsParseRoundTripAndNameTheFieldOnError) {
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(minimal(), c));
  ASSERT_EQ(c.engines.size(), 1u);  // default: Simbody alone
  EXPECT_EQ(c.engines[0], sim::EngineKind::kSimbody);
  EXPECT_EQ(c.validate_seeds, 10);
  auto d = minimal();
  d["engine"] = "mujoco";
  ASSERT_TRUE(parse_task_config(d, c));
  EXPECT_EQ(c.engines, std::vector<sim::EngineKind>{sim::EngineKind::kMujoco});
  d = minimal();
  d["engines"] = {"simbody", "mujoco"};
  d["trials"] = 3;
  d["validate"] = {{"seeds", 4}};
  ASSERT_TRUE(parse_task_config(d, c));
  EXPECT_EQ(c.world_count(), 6);
  EXPECT_EQ(c.validate_seeds, 4);
  TaskConfig back;
  ASSERT_TRUE(parse_task_config(to_json(c), back));
  EXPECT_EQ(back.engines, c.engines);
  EXPECT_EQ(back.validate_seeds, 4);
  EXPECT_EQ(to_json(back), to_json(c));
  // World k: engine k / trials, seed trial_seed + k % trials (both engines see the same seeds).
  const RobotTask task(c);
  for (int k = 0; k < c.world_count(); ++k) {
    const sim::WorldOptions w = task.world_options(k);
    EXPECT_EQ(w.engine, k < 3 ? sim::EngineKind::kSimbody : sim::EngineKind::kMujoco) << k;
    EXPECT_EQ(w.seed, c.trial_seed + static_cast<std::uint64_t>(k % 3)) << k;
  }
  d = minimal();
  d["engine"] = "bullet";
  EXPECT_EQ(error_of(d), "engine: expected simbody or mujoco, got 'bullet'");
  d = minimal();
  d["engines"] = {"simbody", "ode"};
  EXPECT_EQ(error_of(d), "engines[1]: expected simbody or mujoco, got 'ode'");
  d = minimal();
  d["engines"] = {"mujoco", "mujoco"};
  EXPECT_EQ(error_of(d), "engines[1]: 'mujoco' appears twice");
  d = minimal();
  d["engines"] = nlohmann::json::array();
  EXPECT_EQ(error_of(d), "engines: must be a non-empty array of engine names");
  d = minimal();
  d["engine"] = "simbody";
  d["engines"] = {"simbody"};
  EXPECT_EQ(error_of(d), "engines: give either engine or engines, not both");
  d = minimal();
  d["validate"] = {{"seeds", 0}};
  EXPECT_EQ(error_of(d), "validate.seeds: must be an integer in [1, 1000]");
  d = minimal();
  d["validate"] = {{"worlds", 2}};
  EXPECT_EQ(error_of(d), "validate.worlds: unknown field");
}

// The simulated robot (issue 20): another URDF (relative to the config file), the named world
// (issue 29: faithful by default, seed by name), the servo law, the IMU and the physics step
// reach every trial's world and survive run.json.
// The ground range (issue 41 point 1) flows to the randomised trials like the friction range,
// not to a single nominal trial; the table checks it; a world object may not set it.
TEST(RunReport, NonDominatedAndKnee) {
  const auto front = non_dominated({{3, 1}, {1, 3}, {2, 2}, {2.5, 2.5}, {4, 4}, {1, 5}});
  ASSERT_EQ(front.size(), 3u);
  EXPECT_EQ(front[0], (std::vector<double>{1, 3}));
  EXPECT_EQ(front[2], (std::vector<double>{3, 1}));
  EXPECT_EQ(knee_index(front), 1u);  // (2, 2) is closest to the ideal point
}

// A kick run's summary names its picks after the kick's objectives (Obj1 sway, Obj2 1/distance);
// a walk run's after the walk's.
TEST(RunReport, SummaryNamesThePicksAfterTheTask) {
  for (const std::string task : {"kick", "walk", "walk-omni"}) {
    test::TempDir tmp;
    tmp.write("run.json", R"({"problem":")" + task + R"(","start":{"reals":[0.5]}})");
    tmp.write("evaluations.jsonl",
              R"({"generation":1,"reals":[0.5],"objectives":[4.0,1.25],"violation":0})"
              "\n"
              R"({"generation":1,"reals":[0.7],"objectives":[3.0,0.5],"violation":0})"
              "\n");
    tmp.write("pareto.csv", "f1,f2,g1\n3.5,0.25,0.6\n2.5,0.5,0.8\n3.0,0.3,0.7\n");
    nlohmann::json summary;
    ASSERT_TRUE(summarise_run(tmp.path(), summary).is_ok());
    EXPECT_EQ(summary["task"], task);
    EXPECT_EQ(summary["ind_o"]["objectives"], (std::vector<double>{4.0, 1.25}));
    const RunPickNames names = run_pick_names(task);
    EXPECT_EQ(std::string(names.best_obj1), task == "kick" ? "least_sway" : "fastest");
    EXPECT_EQ(std::string(names.best_obj2), task == "kick" ? "longest_kick" : "most_stable");
    EXPECT_EQ(summary[names.best_obj1]["file"], "front/001.json");  // Obj1 2.5
    EXPECT_EQ(summary[names.best_obj2]["file"], "front/000.json");  // Obj2 0.25: 4 m
    EXPECT_EQ(summary["knee"]["file"], "front/002.json");
    EXPECT_FALSE(summary.contains(task == "kick" ? "fastest" : "least_sway"));
  }
}

TEST(Progress, LineShowsGenerationRateEtaBestAndHypervolume) {
  GenerationRecord r;
  r.generation = 3;
  r.generations = 10;
  r.evaluations = 24;
  r.hypervolume = 0.5;
  r.best_objectives = {21.5, 12.25};
  const std::string plain = ProgressPrinter(false).line(r, 2.5, 70);
  EXPECT_NE(plain.find("generation 3/10"), std::string::npos) << plain;
  EXPECT_NE(plain.find("2.50 evals/s"), std::string::npos) << plain;
  EXPECT_NE(plain.find("ETA 70 s"), std::string::npos) << plain;
  EXPECT_NE(plain.find("best 21.5 12.25"), std::string::npos) << plain;
  EXPECT_NE(plain.find("hypervolume 0.500000"), std::string::npos) << plain;
  EXPECT_EQ(plain.find('['), std::string::npos);
  EXPECT_EQ(ProgressPrinter(true).line(r, 2.5, 70).rfind("[#######", 0), 0u);
}

}  // namespace
}  // namespace stride::opt
