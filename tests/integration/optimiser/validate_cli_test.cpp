// `stride validate` on a tiny real walk run (pop 4, 2 generations, 2 s episodes): the result is
// the same for any thread count and equals what `stride optimise` wrote at the end of the run;
// the gate and gain-kept fields agree with the medians; `stride report` shows the table; a
// world that explodes is a fall with its reason; bad input is one line and exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "read_file.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
const std::string kStride = std::string(STRIDE_BIN_DIR) + "/stride";
const std::string kConfigs = std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/";

/// Runs `stride ARGS`, stderr to `err`; returns stdout and sets `code`.
std::string stride(const std::string& args, const fs::path& err, int& code) {
  return test::run_command(kStride + " " + args + " 2>" + err.string(), code);
}

/// walk.json with 2 s episodes, a 0.3 m goal, pop 4, 2 generations, 3 validation seeds.
fs::path tiny_walk_config(const fs::path& dir, const char* world = "faithful") {
  std::ifstream in(kConfigs + "walk.json");
  json c = json::parse(in);
  c["world"] = world;
  c["pop"] = 4;
  c["generations"] = 2;
  c["duration_s"] = 2.0;
  c["goal_distance_m"] = 0.3;
  c["pm"] = 0.2;
  c["validate"] = {{"seeds", 3}};
  const fs::path path = dir / "walk-tiny.json";
  std::ofstream(path) << c.dump(1);
  return path;
}

int lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

TEST(ValidateCli, TinyWalkRunValidatesTheSameForAnyThreadCountAndReportShowsIt) {
  test::TempDir tmp;
  const fs::path run = tmp.path() / "run", err = tmp.path() / "stderr";
  int code = -1;
  stride("optimise --config " + tiny_walk_config(tmp.path()).string() + " --out " + run.string() +
             " --jobs 2",
         err, code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  // stride optimise validated at the end (3 seeds from the config).
  ASSERT_TRUE(fs::exists(run / "validation.json")) << test::read_file(err);
  const std::string by_optimise = test::read_file(run / "validation.json");
  stride("validate " + run.string() + " --jobs 1", err, code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  EXPECT_EQ(test::read_file(run / "validation.json"),
            by_optimise);  // 2 threads then 1: the same file
  const std::string printed = stride("validate " + run.string() + " --jobs 2 --json", err, code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  EXPECT_EQ(test::read_file(run / "validation.json"), by_optimise);
  const json v = json::parse(printed);
  EXPECT_EQ(v, json::parse(by_optimise));
  EXPECT_NE(test::read_file(err).find("validate: "), std::string::npos);  // progress on stderr

  EXPECT_EQ(v["format"], "stride-validation-2");
  EXPECT_EQ(v["task"], "walk");
  EXPECT_EQ(v["run_engines"], json({"simbody"}));
  // The worlds: the other engine, fresh seeds, wider randomisation, the servos off the model
  // (issue 54), half the run's 2.5 ms step
  // (the walk's trial step), the soft and the hard ground. Each world's options are a `world`
  // object of the world option table's keys: what differs from the defaults (Simbody, no
  // ranges, the base world's ground, noise on).
  const json& worlds = v["worlds"];
  ASSERT_EQ(worlds.size(), 7u);
  auto option = [&worlds](std::size_t w, const char* key) {
    return worlds[w]["world"].contains(key) ? worlds[w]["world"][key] : json();
  };
  EXPECT_EQ(worlds[0]["name"], "engine mujoco");
  EXPECT_EQ(option(0, "engine"), "mujoco");
  EXPECT_EQ(option(0, "physics_step_us"), 2000);  // the step the walk allows on MuJoCo
  EXPECT_EQ(worlds[1]["name"], "fresh seeds");
  EXPECT_EQ(worlds[2]["name"], "wider randomisation");
  EXPECT_DOUBLE_EQ(option(2, "friction_range").get<double>(), 0.3);
  EXPECT_DOUBLE_EQ(option(2, "mass_range").get<double>(), 0.075);
  EXPECT_DOUBLE_EQ(option(2, "strength_range").get<double>(), 0.15);
  EXPECT_DOUBLE_EQ(option(2, "latency_probability").get<double>(), 0.5);
  EXPECT_EQ(worlds[3]["name"], "servos off the model");
  EXPECT_DOUBLE_EQ(option(3, "servo_friction_min").get<double>(), 0.8);
  EXPECT_DOUBLE_EQ(option(3, "servo_friction_max").get<double>(), 1.6);
  EXPECT_DOUBLE_EQ(option(3, "servo_torque_min").get<double>(), 0.8);
  EXPECT_DOUBLE_EQ(option(3, "servo_torque_max").get<double>(), 1.05);
  EXPECT_DOUBLE_EQ(option(3, "supply_min").get<double>(), 12.0);
  EXPECT_DOUBLE_EQ(option(3, "supply_max").get<double>(), 16.8);
  EXPECT_DOUBLE_EQ(option(3, "latency_probability").get<double>(), 0.5);
  EXPECT_EQ(worlds[4]["name"], "half step");
  EXPECT_EQ(option(4, "physics_step_us"), 1250);
  for (std::size_t w = 0; w < 5; ++w) {
    EXPECT_EQ(option(w, "base"), "faithful");  // its ground: turf
    EXPECT_TRUE(option(w, "contact").is_null()) << worlds[w]["name"];
  }
  EXPECT_EQ(worlds[5]["name"], "ground soft");
  EXPECT_EQ(option(5, "contact"), "soft");
  EXPECT_EQ(worlds[6]["name"], "ground hard");
  EXPECT_EQ(option(6, "contact"), "hard");
  for (std::size_t w = 5; w < 7; ++w) {
    EXPECT_TRUE(option(w, "engine").is_null());  // the run's engine (Simbody), step, ranges
    EXPECT_EQ(option(w, "physics_step_us"), 2500);
    EXPECT_EQ(option(w, "friction"), 1.0);  // turf's, the run's ground's
    EXPECT_EQ(option(w, "friction_range"), option(1, "friction_range"));
    EXPECT_TRUE(option(w, "contact_range").is_null());
  }
  for (std::size_t w = 0; w < worlds.size(); ++w) {
    EXPECT_EQ(worlds[w]["seeds"], json({1001, 1002, 1003}))
        << worlds[w]["name"];              // trial_seed 1 + 1000 + i
    EXPECT_EQ(option(w, "seed"), 1001);    // the record is the first seed's world
    EXPECT_NE(option(w, "noise"), "off");  // on (the default) in every world
    EXPECT_FALSE(worlds[w].contains("imu_noise"));
    EXPECT_FALSE(worlds[w].contains("unavailable")) << worlds[w]["name"];
  }
  // Ind_O first, then the picks of `stride report`.
  const json& individuals = v["individuals"];
  ASSERT_GE(individuals.size(), 2u);
  EXPECT_EQ(individuals[0]["name"], "Ind_O");
  EXPECT_EQ(individuals[0]["file"], "");
  EXPECT_EQ(v["table"].size(), individuals.size() * worlds.size());
  bool all_passed = true;
  for (std::size_t i = 0; i < individuals.size(); ++i) {
    const json& ind = individuals[i];
    ASSERT_EQ(ind["worlds"].size(), worlds.size());
    const double own = ind["run_objectives"][0].get<double>();
    for (std::size_t w = 0; w < worlds.size(); ++w) {
      const json& cell = ind["worlds"][w];
      SCOPED_TRACE(ind["name"].get<std::string>() + " / " + cell["world"].get<std::string>());
      EXPECT_EQ(cell["world"], worlds[w]["name"]);
      EXPECT_EQ(cell["seeds"], 3);
      const int reached = cell["reached"], falls = cell["falls"];
      EXPECT_LE(reached + falls, 3);
      EXPECT_DOUBLE_EQ(cell["reached_fraction"].get<double>(), reached / 3.0);
      const json& gate = cell["gate"];
      EXPECT_DOUBLE_EQ(gate["limit"].get<double>(), own + 0.25 * std::abs(own));
      EXPECT_EQ(gate["median"], cell["median_objectives"][0]);
      const bool pass = reached >= 3 && gate["median"].get<double>() <= gate["limit"].get<double>();
      EXPECT_EQ(gate["passed"].get<bool>(), pass);
      all_passed = all_passed && pass;
      // Gain kept: picks only, only where Ind_O passes the gate, by the formula.
      const json& ind_o_cell = individuals[0]["worlds"][w];
      if (i == 0 || !ind_o_cell["gate"]["passed"].get<bool>()) {
        EXPECT_TRUE(cell["gain_kept"].is_null());
        continue;
      }
      ASSERT_TRUE(cell["gain_kept"].is_array());
      for (int m = 0; m < 2; ++m) {
        const double run_gain = individuals[0]["run_objectives"][m].get<double>() -
                                ind["run_objectives"][m].get<double>();
        const double gain = ind_o_cell["median_objectives"][m].get<double>() -
                            cell["median_objectives"][m].get<double>();
        if (std::abs(run_gain) > 1e-12) {
          EXPECT_NEAR(cell["gain_kept"][m].get<double>(), gain / run_gain, 1e-12);
        } else {
          EXPECT_TRUE(cell["gain_kept"][m].is_null());
        }
      }
    }
  }
  EXPECT_EQ(v["all_passed"].get<bool>(), all_passed);

  // stride report: the table in the text, the JSON and report.html.
  const std::string text = stride("report " + run.string(), err, code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  EXPECT_NE(text.find("validation of a walk run"), std::string::npos) << text;
  EXPECT_NE(text.find("wider randomisation"), std::string::npos) << text;
  EXPECT_NE(text.find("ground hard"), std::string::npos) << text;
  // ... then in words: a line per individual, what pass and fail mean.
  EXPECT_NE(text.find("in words:\n  Ind_O: "), std::string::npos) << text;
  EXPECT_NE(text.find("\npass (holds): at least 80 % of the seeds reach the goal"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\nfail: "), std::string::npos) << text;
  const json summary = json::parse(stride("report " + run.string() + " --json", err, code));
  EXPECT_EQ(summary["validation"], v);
  const std::string html = test::read_file(run / "report.html");
  EXPECT_NE(html.find("id=\"validation-table\""), std::string::npos);
  EXPECT_NE(html.find("id=\"validation-worlds\""), std::string::npos);
  EXPECT_NE(html.find("half step"), std::string::npos);
}

TEST(ValidateCli, AnExplodingWorldIsAFallWithItsReasonAndNoValidateWritesNothing) {
  test::TempDir tmp;
  const fs::path run = tmp.path() / "run", err = tmp.path() / "stderr";
  int code = -1;
  // Pins the seed's world: its servo law explodes at a 10 ms step (the identified one, whose
  // back-EMF damps the motor, does not).
  stride("optimise --config " + tiny_walk_config(tmp.path(), "seed").string() + " --out " +
             run.string() + " --jobs 2 --no-validate",
         err, code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  EXPECT_FALSE(fs::exists(run / "validation.json"));
  // A 10 ms step: the stiff servos explode the world at once; a fall with its reason, exit 0.
  const json v = json::parse(stride(
      "validate " + run.string() + " --seeds 2 --physics-step-us 10000 --engine simbody --json",
      err, code));
  ASSERT_EQ(code, 0) << test::read_file(err);
  ASSERT_EQ(v["worlds"].size(), 7u);
  EXPECT_EQ(v["worlds"][0]["name"], "engine simbody");  // --engine replaces the list
  EXPECT_EQ(v["worlds"][4]["name"], "step 10000 us");
  for (const json& ind : v["individuals"]) {
    const json& cell = ind["worlds"][4];
    EXPECT_EQ(cell["falls"], 2);
    EXPECT_EQ(cell["reached"], 0);
    EXPECT_FALSE(cell["gate"]["passed"].get<bool>());
    ASSERT_EQ(cell["failures"].size(), 2u);
    EXPECT_EQ(cell["failures"][0]["seed"], 1001);
    EXPECT_NE(cell["failures"][0]["reason"].get<std::string>().find("exploding"),
              std::string::npos);
  }
  EXPECT_FALSE(v["all_passed"].get<bool>());
}

// A robot run extended with --resume --generations (its task records the settings too) equals
// the longer run from the start, validation included.
TEST(ValidateCli, AnExtendedRobotRunEqualsTheLongerRun) {
  test::TempDir tmp;
  const fs::path err = tmp.path() / "stderr";
  int code = -1;
  const std::string config = tiny_walk_config(tmp.path()).string();
  stride("optimise --config " + config + " --generations 1 --jobs 2 --out " +
             (tmp.path() / "extended").string(),
         err, code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  stride("optimise --out " + (tmp.path() / "extended").string() + " --resume --generations 2", err,
         code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  stride("optimise --config " + config + " --generations 2 --jobs 2 --out " +
             (tmp.path() / "direct").string(),
         err, code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  for (const char* file :
       {"evaluations.jsonl", "pareto.csv", "run.json", "checkpoint.json", "validation.json"})
    EXPECT_EQ(test::read_file(tmp.path() / "extended" / file),
              test::read_file(tmp.path() / "direct" / file))
        << file;
}

TEST(ValidateCli, BadInputIsOneLineNamingItAndExitTwo) {
  test::TempDir tmp;
  const fs::path run = tmp.path() / "run", err = tmp.path() / "stderr";
  int code = -1;
  stride("optimise --config " + tiny_walk_config(tmp.path()).string() + " --out " + run.string() +
             " --jobs 2 --no-validate --generations 1",
         err, code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  auto expect_bad = [&](const std::string& args, const std::string& says) {
    stride("validate " + args, err, code);
    EXPECT_EQ(code, 2) << args;
    const std::string e = test::read_file(err);
    EXPECT_EQ(lines(e), 1) << e;
    EXPECT_NE(e.find(says), std::string::npos) << e;
  };
  expect_bad(tmp.path().string(), "is not a run directory (no run.json)");
  expect_bad(run.string() + " --engine bullet",
             "--engine: expected simbody or mujoco, got 'bullet'");
  expect_bad(run.string() + " --engine simbody --engine=ode",
             "--engine: expected simbody or mujoco, got 'ode'");
  expect_bad(
      run.string() + " --physics-step-us 3000",
      "--physics-step-us: 3000 us does not divide the firmware's control period of 10000 us");
  expect_bad(run.string() + " --physics-step-us 0",
             "--physics-step-us: must be in 1..20000 us, got 0");
  expect_bad(run.string() + " --member x",
             "--member: expected a pareto.csv row (0, 1, ...), got 'x'");
  expect_bad(run.string() + " --member 999", "--member: 999 is not a front row (pareto.csv has ");
  // Every front member once: Ind_O, then the picks, then the other rows by their files.
  const std::string csv = test::read_file(run / "pareto.csv");
  const int rows = lines(csv) - 1;
  ASSERT_GE(rows, 1);
  std::string all;
  for (int r = 0; r < rows; ++r) all += " --member " + std::to_string(r);
  const json v =
      json::parse(stride("validate " + run.string() + all + " --seeds 1 --json", err, code));
  ASSERT_EQ(code, 0) << test::read_file(err);
  ASSERT_EQ(v["individuals"].size(), static_cast<std::size_t>(1 + rows)) << v["individuals"].dump();
  for (std::size_t i = 1; i < v["individuals"].size(); ++i)
    EXPECT_EQ(v["individuals"][i]["file"].get<std::string>().rfind("front/", 0), 0u);
  fs::remove(run / "validation.json");
  expect_bad(run.string() + " --seeds 0", "--seeds: 0 is outside [1, 1000]");
  expect_bad("", "expected one run directory");
  EXPECT_FALSE(fs::exists(run / "validation.json"));
  // A run that is not a robot run.
  stride("optimise --problem zdt1 --pop 8 --generations 2 --out " + (tmp.path() / "zdt1").string(),
         err, code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  expect_bad((tmp.path() / "zdt1").string(), "is a 'zdt1' run, not a robot run");
  // A robot run without picks (no front members).
  fs::remove(run / "pareto.csv");
  expect_bad(run.string(), "has no picks to validate");
  EXPECT_FALSE(fs::exists(run / "validation.json"));
  // An unknown engine in a config: one line naming the field, exit 2.
  json c = json::parse(test::read_file(tiny_walk_config(tmp.path())));
  c["engine"] = "bullet";
  std::ofstream(tmp.path() / "bad.json") << c.dump();
  stride("optimise --config " + (tmp.path() / "bad.json").string() + " --out " +
             (tmp.path() / "bad").string(),
         err, code);
  EXPECT_EQ(code, 2);
  EXPECT_EQ(lines(test::read_file(err)), 1);
  EXPECT_NE(test::read_file(err).find("engine: expected simbody or mujoco, got 'bullet'"),
            std::string::npos)
      << test::read_file(err);
  stride("optimise --config " + tiny_walk_config(tmp.path()).string() + " --engine ode --out " +
             (tmp.path() / "bad").string(),
         err, code);
  EXPECT_EQ(code, 2);
  EXPECT_NE(test::read_file(err).find("--engine: expected simbody or mujoco, got 'ode'"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(tmp.path() / "bad"));
  // --engine takes a list, as stride validate's: every trial on both engines.
  json one = json::parse(test::read_file(tiny_walk_config(tmp.path())));
  one["generations"] = 1;
  std::ofstream(tmp.path() / "one.json") << one.dump();
  stride("optimise --config " + (tmp.path() / "one.json").string() +
             " --engine simbody,mujoco --engine mujoco --no-validate --out " +
             (tmp.path() / "both").string(),
         err, code);
  ASSERT_EQ(code, 0) << test::read_file(err);
  const json recorded = json::parse(test::read_file(tmp.path() / "both" / "run.json"));
  EXPECT_EQ(recorded["task"]["engines"], json::array({"simbody", "mujoco"})) << recorded.dump();
}

}  // namespace
}  // namespace stride::opt
