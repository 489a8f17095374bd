// Task configs through run.json (issue 44 point 1): every shipped config, written as
// `stride optimise` writes run.json and read back as --resume and `stride validate` read it,
// keeps every value its file gives and reads back field by field as it was loaded; every task
// setting set away from its default survives the trip (so that a field the writer drops is seen
// even where the defaults would hide it); an issue-32 ramp (a normalised increment) still loads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "stride/optimiser/run/optimisation_run.hpp"
#include "stride/optimiser/tasks/kick_settings.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "stride/optimiser/tasks/speed_ramp.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
#include "stride/optimiser/tasks/walk_command_settings.hpp"
#include "stride/optimiser/tasks/walk_omni_settings.hpp"
#include "stride/optimiser/tasks/walk_settings.hpp"
#include "stride/sim_hal/world_spec.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

using nlohmann::json;

const std::filesystem::path kConfigs =
    std::filesystem::path(STRIDE_SOURCE_DIR) / "optimiser/configs";

/// Writes `config` to dir/run.json the way `stride optimise` does and returns the task config
/// that read_run_config gives back, as JSON.
json through_run_json(const TaskConfig& config, const std::filesystem::path& dir) {
  const RobotTask task(config);
  RunConfig run;
  run.problem = config.task;
  run.settings = config.settings;
  run.start = task.start_genome();
  run.task = to_json(config);
  std::ofstream(dir / "run.json") << run_description(task, run).dump(2) << "\n";
  RunConfig back;
  EXPECT_TRUE(read_run_config(dir, back));
  return back.task;
}

/// Every value the original file gives (comments aside) stands at the same place in `written`:
/// a field that the writer drops, or writes differently, is named.
void expect_contains(const json& original, const json& written, const std::string& where) {
  if (original.is_object()) {
    ASSERT_TRUE(written.is_object()) << where << " is not an object in run.json";
    for (const auto& [key, value] : original.items()) {
      if (key == "_comment") continue;
      const std::string field = where.empty() ? key : where + "." + key;
      if (!written.contains(key)) {
        ADD_FAILURE() << field << " is in the config but not in run.json";
        continue;
      }
      expect_contains(value, written.at(key), field);
    }
  } else if (original.is_array()) {
    ASSERT_TRUE(written.is_array()) << where << " is not an array in run.json";
    ASSERT_EQ(original.size(), written.size()) << where;
    for (std::size_t i = 0; i < original.size(); ++i)
      expect_contains(original[i], written[i], where + "[" + std::to_string(i) + "]");
  } else if (original.is_number()) {
    ASSERT_TRUE(written.is_number()) << where << ": " << written.dump();
    EXPECT_EQ(original.get<double>(), written.get<double>()) << where;
  } else {
    EXPECT_EQ(original, written) << where;
  }
}

/// The straightness limits a walking task's settings hold, field by field.
void expect_same(const StraightnessLimits& a, const StraightnessLimits& b) {
  EXPECT_EQ(a.max_drift_ratio, b.max_drift_ratio);
  EXPECT_EQ(a.max_heading_change_deg, b.max_heading_change_deg);
  EXPECT_EQ(a.max_turn_translation_m, b.max_turn_translation_m);
}

/// Every field of the config read back equals the loaded config's, named when it does not (the
/// world through its JSON, which names its fields).
void expect_same(const TaskConfig& a, const TaskConfig& b) {
  EXPECT_EQ(a.task, b.task);
  EXPECT_TRUE(a.settings == b.settings) << "NSGA-II settings";
  ASSERT_EQ(a.genes.size(), b.genes.size());
  for (std::size_t i = 0; i < a.genes.size(); ++i) {
    EXPECT_EQ(a.genes[i].parameter, b.genes[i].parameter) << "genes[" << i << "]";
    EXPECT_EQ(a.genes[i].min, b.genes[i].min) << "genes[" << i << "]";
    EXPECT_EQ(a.genes[i].max, b.genes[i].max) << "genes[" << i << "]";
    EXPECT_EQ(a.genes[i].start, b.genes[i].start) << "genes[" << i << "]";
  }
  EXPECT_EQ(a.duration_s, b.duration_s);
  // The task's own settings: whole (a defaulted ==, so a field added is compared), and named.
  EXPECT_TRUE(a.own == b.own) << "the task's own settings";
  EXPECT_EQ(a.own.empty(), b.own.empty());
  if (const KickSettings* k = a.own.find<KickSettings>()) {
    const KickSettings& r = b.own_settings<KickSettings>();
    EXPECT_EQ(k->script, r.script);
    EXPECT_EQ(k->kick_at_s, r.kick_at_s);
    EXPECT_EQ(k->yaw_drift_limit_rad, r.yaw_drift_limit_rad);
  }
  if (const WalkSettings* w = a.own.find<WalkSettings>()) {
    const WalkSettings& r = b.own_settings<WalkSettings>();
    EXPECT_EQ(w->goal_distance_m, r.goal_distance_m);
    EXPECT_EQ(w->walk_vx, r.walk_vx);
    expect_same(w->straightness, r.straightness);
  }
  if (const OmniSettings* o = a.own.find<OmniSettings>()) {
    const OmniTiming& r = b.own_settings<OmniSettings>().timing;
    EXPECT_EQ(o->timing.start_s, r.start_s);
    EXPECT_EQ(o->timing.ramp_s, r.ramp_s);
    EXPECT_EQ(o->timing.hold_s, r.hold_s);
    EXPECT_EQ(o->timing.stop_s, r.stop_s);
    expect_same(o->straightness, b.own_settings<OmniSettings>().straightness);
  }
  if (const RampSettings* p = a.own.find<RampSettings>()) {  // every field, named
    EXPECT_EQ(to_json(p->timing), to_json(b.own_settings<RampSettings>().timing));
    expect_same(p->straightness, b.own_settings<RampSettings>().straightness);
  }
  EXPECT_EQ(a.trials, b.trials);
  EXPECT_EQ(a.aggregate, b.aggregate);
  EXPECT_EQ(a.trial_seed, b.trial_seed);
  EXPECT_EQ(a.randomisation.imu_noise, b.randomisation.imu_noise);
  EXPECT_EQ(a.randomisation.friction_range, b.randomisation.friction_range);
  EXPECT_EQ(a.randomisation.mass_range, b.randomisation.mass_range);
  EXPECT_EQ(a.randomisation.strength_range, b.randomisation.strength_range);
  EXPECT_EQ(a.randomisation.contact_range, b.randomisation.contact_range);
  EXPECT_EQ(a.randomisation.com_range, b.randomisation.com_range);
  EXPECT_EQ(a.engines, b.engines);
  EXPECT_EQ(sim::to_json(a.world), sim::to_json(b.world));
  EXPECT_EQ(a.base_params, b.base_params);
  ASSERT_EQ(a.starts.size(), b.starts.size());
  for (std::size_t i = 0; i < a.starts.size(); ++i) {
    EXPECT_EQ(a.starts[i].firmware_defaults, b.starts[i].firmware_defaults)
        << "starts[" << i << "]";
    EXPECT_EQ(a.starts[i].values, b.starts[i].values) << "starts[" << i << "]";
  }
  EXPECT_EQ(a.validate_seeds, b.validate_seeds);
  EXPECT_EQ(a.hv_ideal, b.hv_ideal);
  EXPECT_EQ(a.hv_nadir, b.hv_nadir);
}

TEST(TaskConfig, EveryShippedConfigKeepsEveryValueThroughRunJson) {
  int configs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kConfigs)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().filename().string());
    ++configs;
    json original;
    std::ifstream(entry.path()) >> original;
    TaskConfig loaded, reread;
    ASSERT_TRUE(load_task_config(entry.path(), loaded));
    const test::TempDir tmp;
    const json written = through_run_json(loaded, tmp.path());
    expect_contains(original, written, "");
    ASSERT_TRUE(parse_task_config(written, reread));
    expect_same(loaded, reread);
    // What the reader rebuilds writes the same record again (nothing lost on a second trip).
    EXPECT_EQ(to_json(reread), written);
  }
  EXPECT_EQ(configs, 12);  // every shipped config was read
}

TEST(TaskConfig, EveryTaskSettingAwayFromItsDefaultSurvivesRunJson) {
  // Each task's own settings set away from their defaults, so that a setting the writer drops
  // (and the reader then defaults) is seen even where no shipped config gives it.
  const auto through = [](const std::string& file, const auto& change) {
    SCOPED_TRACE(file);
    TaskConfig config, reread;
    ASSERT_TRUE(load_task_config(kConfigs / file, config));
    change(config);
    const test::TempDir tmp;
    ASSERT_TRUE(parse_task_config(through_run_json(config, tmp.path()), reread));
    expect_same(config, reread);
  };
  through("kick.json", [](TaskConfig& c) {
    KickSettings& k = c.own_settings<KickSettings>();
    k.script = "kick_left";
    k.kick_at_s = 1.5;
    k.yaw_drift_limit_rad = 3.25;
  });
  through("walk.json", [](TaskConfig& c) {
    WalkSettings& w = c.own_settings<WalkSettings>();
    w.goal_distance_m = 1.75;
    w.walk_vx = 0.625;
    w.straightness = {0.2, -1.0, 0.05};  // heading off: null
  });
  through("walk-omni.json", [](TaskConfig& c) {
    c.own_settings<OmniSettings>().timing = {3.0, 0.5, 6.0, 1.5};
    c.own_settings<OmniSettings>().straightness = {-1.0, 12.5, 0.15};
  });
  through("walk-ramp.json", [](TaskConfig& c) {
    c.own_settings<RampSettings>().timing = {1.5, 0.03, 0.15, 0.125, 5.0, 2.5, 12, 5};
    c.own_settings<RampSettings>().straightness = {0.15, 7.5, -1.0};
  });
  through("walk-command.json", [](TaskConfig& c) {
    CommandSchedule& s = c.own_settings<CommandSettings>().schedule;
    s = {1.5, 3.0, 2.0, 0.75, s.segments};
    s.segments.push_back({"sidestep", {0.25, -0.5, 0.0}});
    s.segments.push_back({"halt", {}, true});
    c.own_settings<CommandSettings>().straightness = {0.2, -1.0, 0.05};
  });
}

TEST(TaskConfig, ARunJsonHoldsOnlyItsOwnTasksSettings) {
  const auto written = [](const std::string& file) {
    TaskConfig config;
    EXPECT_TRUE(load_task_config(kConfigs / file, config));
    const test::TempDir tmp;
    return through_run_json(config, tmp.path());
  };
  const json walk = written("walk.json");
  EXPECT_TRUE(walk.contains("goal_distance_m"));
  EXPECT_TRUE(walk.contains("walk_vx"));
  for (const char* kick_field : {"script", "kick_at_s", "yaw_drift_limit_rad"})
    EXPECT_FALSE(walk.contains(kick_field)) << kick_field;
  const json kick = written("kick.json");
  EXPECT_EQ(kick.at("script"), "kick_right");
  for (const char* walk_field : {"goal_distance_m", "walk_vx", "omni", "ramp", "max_drift_ratio",
                                 "max_heading_change_deg", "max_turn_translation_m"})
    EXPECT_FALSE(kick.contains(walk_field)) << walk_field;
  // The straightness limits: the walking tasks' own (walk, walk-omni, walk-ramp), no other's.
  for (const char* file : {"walk.json", "walk-omni.json", "walk-ramp.json"})
    for (std::string_view field : kStraightnessFields)
      EXPECT_TRUE(written(file).contains(std::string(field))) << file << ": " << field;
  for (std::string_view field : kStraightnessFields)
    EXPECT_FALSE(written("getup.json").contains(std::string(field))) << field;
  EXPECT_FALSE(walk.contains("omni"));
  EXPECT_FALSE(walk.contains("ramp"));
  EXPECT_TRUE(written("walk-omni.json").contains("omni"));
  EXPECT_FALSE(written("walk-omni.json").contains("ramp"));
  EXPECT_TRUE(written("walk-ramp.json").contains("ramp"));
}

TEST(TaskConfig, AnOldRunJsonWithEveryTasksFieldsStillLoads) {
  // Before the tasks owned their settings, every run.json held every task's fields: its record
  // still loads (parse_task_record, as --resume, report and validate read it), the others' left
  // out; a config file that gives them is an error (task_registry_test.cpp).
  json doc;
  std::ifstream(kConfigs / "walk.json") >> doc;
  doc["script"] = "kick_right";
  doc["kick_at_s"] = 1.0;
  doc["yaw_drift_limit_rad"] = 6.66;
  doc["walk_vx"] = 0.75;
  doc["omni"] = {{"hold_s", 0.5}};  // walk-omni's, and one it would refuse: not read
  doc["ramp"] = {{"measure_s", 3.0}, {"increment", 0.1}};  // walk-ramp's (issue 32's)
  TaskConfig c;
  ASSERT_TRUE(parse_task_record(doc, c));
  EXPECT_EQ(c.own_settings<WalkSettings>().walk_vx, 0.75);
  EXPECT_EQ(c.own.find<KickSettings>(), nullptr);
  std::ifstream(kConfigs / "kick.json") >> doc;
  doc["goal_distance_m"] = 2.5;
  doc["walk_vx"] = 1.0;
  doc["kick_at_s"] = 2.0;
  doc["max_drift_ratio"] = -0.5;  // the walking tasks' (one they would refuse): not read
  doc["omni"] = {{"pause_s", 1.0}};
  ASSERT_TRUE(parse_task_record(doc, c));
  EXPECT_EQ(c.own_settings<KickSettings>().kick_at_s, 2.0);
  // A task's own setting is still checked; another task's is not read.
  doc["kick_at_s"] = 9.0;
  const Status s = parse_task_record(doc, c);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(), "kick_at_s: must be in [0, duration_s)");
}

TEST(TaskConfig, EveryRampSettingSurvivesRunJson) {
  TaskConfig config, reread;
  ASSERT_TRUE(load_task_config(kConfigs / "walk-ramp.json", config));
  // None of them the default (RampTiming's), so that a field the writer drops is seen.
  RampTiming& ramp = config.own_settings<RampSettings>().timing;
  ramp = {.start_s = 1.5,
          .increment_mps = 0.03,
          .increment_radps = 0.15,
          .increment = 0.0,
          .hold_s = 5.0,
          .measure_s = 2.5,
          .max_levels = 12,
          .patience = 5};
  const test::TempDir tmp;
  ASSERT_TRUE(parse_task_config(through_run_json(config, tmp.path()), reread));
  const RampTiming& back = reread.own_settings<RampSettings>().timing;
  EXPECT_EQ(back.start_s, 1.5);
  EXPECT_EQ(back.increment_mps, 0.03);
  EXPECT_EQ(back.increment_radps, 0.15);
  EXPECT_EQ(back.increment, 0.0);
  EXPECT_FALSE(back.normalised());
  EXPECT_EQ(back.hold_s, 5.0);
  EXPECT_EQ(back.measure_s, 2.5);
  EXPECT_EQ(back.max_levels, 12);
  EXPECT_EQ(back.patience, 5);
  EXPECT_TRUE(back == ramp);
  // A normalised ramp (issue 32's) stays one.
  ramp.increment = 0.15;
  ASSERT_TRUE(parse_task_config(through_run_json(config, tmp.path()), reread));
  EXPECT_EQ(reread.own_settings<RampSettings>().timing.increment, 0.15);
  EXPECT_TRUE(reread.own_settings<RampSettings>().timing.normalised());
}

TEST(TaskConfig, AnIssue32RampFromAnOldRunJsonStillLoadsAsTheNormalisedRamp) {
  // The ramp as issue 32's run.json files hold it: a normalised increment, no speeds.
  json doc;
  std::ifstream(kConfigs / "walk-ramp.json") >> doc;
  doc["ramp"] = {{"start_s", 2.0},   {"increment", 0.1}, {"hold_s", 4.0},
                 {"measure_s", 3.0}, {"max_levels", 10}, {"patience", 2}};
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(doc, c));
  EXPECT_TRUE(c.own_settings<RampSettings>().timing.normalised());
  EXPECT_EQ(c.own_settings<RampSettings>().timing.increment, 0.1);
  EXPECT_EQ(c.own_settings<RampSettings>().timing.measure_s, 3.0);
}

TEST(TaskConfig, ABadRampSpeedIsNamed) {
  json doc;
  std::ifstream(kConfigs / "walk-ramp.json") >> doc;
  TaskConfig c;
  json bad = doc;
  bad["ramp"]["increment_mps"] = 0.0;
  Status s = parse_task_config(bad, c);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(), "ramp.increment_mps: must be in (0, 1] m/s");
  bad = doc;
  bad["ramp"]["increment_radps"] = 6.0;
  s = parse_task_config(bad, c);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(), "ramp.increment_radps: must be in (0, 5] rad/s");
  bad = doc;
  bad["ramp"]["increment"] = -0.1;
  s = parse_task_config(bad, c);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(),
            "ramp.increment: must be in [0, 1] (normalised command per level; 0: levels of "
            "increment_mps and increment_radps)");
  bad = doc;
  bad["ramp"]["increment_mps"] = "fast";
  s = parse_task_config(bad, c);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(), "ramp.increment_mps: must be a number, got \"fast\"");
}

}  // namespace
}  // namespace stride::opt
