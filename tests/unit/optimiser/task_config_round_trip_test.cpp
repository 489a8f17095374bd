// Task configs through run.json (issue 44 point 1): every shipped config, written as
// `stride optimise` writes run.json and read back as --resume and `stride validate` read it,
// keeps every value its file gives; every ramp setting survives the trip, and an issue-32 ramp
// (a normalised increment) still loads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "stride/optimiser/run/optimisation_run.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
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
    // What the reader rebuilds writes the same record again (nothing lost on a second trip).
    EXPECT_EQ(to_json(reread), written);
  }
  EXPECT_EQ(configs, 8);
}

TEST(TaskConfig, EveryRampSettingSurvivesRunJson) {
  TaskConfig config, reread;
  ASSERT_TRUE(load_task_config(kConfigs / "walk-ramp.json", config));
  // None of them the default (RampTiming's), so that a field the writer drops is seen.
  config.ramp.start_s = 1.5;
  config.ramp.increment_mps = 0.03;
  config.ramp.increment_radps = 0.15;
  config.ramp.increment = 0.0;
  config.ramp.hold_s = 5.0;
  config.ramp.measure_s = 2.5;
  config.ramp.max_levels = 12;
  config.ramp.patience = 5;
  const test::TempDir tmp;
  ASSERT_TRUE(parse_task_config(through_run_json(config, tmp.path()), reread));
  EXPECT_EQ(reread.ramp.start_s, 1.5);
  EXPECT_EQ(reread.ramp.increment_mps, 0.03);
  EXPECT_EQ(reread.ramp.increment_radps, 0.15);
  EXPECT_EQ(reread.ramp.increment, 0.0);
  EXPECT_FALSE(reread.ramp.normalised());
  EXPECT_EQ(reread.ramp.hold_s, 5.0);
  EXPECT_EQ(reread.ramp.measure_s, 2.5);
  EXPECT_EQ(reread.ramp.max_levels, 12);
  EXPECT_EQ(reread.ramp.patience, 5);
  // A normalised ramp (issue 32's) stays one.
  config.ramp.increment = 0.15;
  ASSERT_TRUE(parse_task_config(through_run_json(config, tmp.path()), reread));
  EXPECT_EQ(reread.ramp.increment, 0.15);
  EXPECT_TRUE(reread.ramp.normalised());
}

TEST(TaskConfig, AnIssue32RampFromAnOldRunJsonStillLoadsAsTheNormalisedRamp) {
  // The ramp as issue 32's run.json files hold it: a normalised increment, no speeds.
  json doc;
  std::ifstream(kConfigs / "walk-ramp.json") >> doc;
  doc["ramp"] = {{"start_s", 2.0},   {"increment", 0.1}, {"hold_s", 4.0},
                 {"measure_s", 3.0}, {"max_levels", 10}, {"patience", 2}};
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(doc, c));
  EXPECT_TRUE(c.ramp.normalised());
  EXPECT_EQ(c.ramp.increment, 0.1);
  EXPECT_EQ(c.ramp.measure_s, 3.0);
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
