// The commanded-walk task (issue 53 point 2): the spline walk's defaults score every segment of
// walk-command.json's schedule in drawn worlds, a genome that falls is infeasible and scores
// lower, a bad setting is one error naming its field, and a short run completes, resumes as the
// uninterrupted run and validates with the task's figures.
//
// Behaviour is judged over drawn worlds: the config's single Simbody trial world of draws 1..5
// (a resampling run's trial is randomised: ground hard to soft, the trunk's centre of mass moved,
// friction, masses, strength, IMU noise). The limits come from 20 draws (1..20) measured with
// WALK_COMMAND_DRAWS=20 (the tests then run those 20; medians, quartiles and counts printed).
// The medians are of the spline walk's defaults at baf45a8; a change of the walk that moves them
// re-measures them so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "read_file.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "stride/optimiser/tasks/walk_command_figures.hpp"
#include "stride/optimiser/tasks/walk_command_settings.hpp"
#include "task_figures_of.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

namespace fs = std::filesystem;
const std::string kConfigs = std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/";
const std::string kBin = std::string(STRIDE_BIN_DIR);

nlohmann::json command_doc() {
  std::ifstream in(kConfigs + "walk-command.json");
  return nlohmann::json::parse(in);
}

TaskConfig command_config() {
  TaskConfig c;
  const Status s = parse_task_config(command_doc(), c);
  EXPECT_TRUE(s) << s.message();
  return c;
}

/// The draws the behavioural tests judge (5; WALK_COMMAND_DRAWS=20 to measure the limits).
int draw_count() {
  const char* n = std::getenv("WALK_COMMAND_DRAWS");
  return n != nullptr ? std::max(1, std::atoi(n)) : 5;
}

/// `genome` in the config's Simbody trial world (WALK_COMMAND_WORLD=1: the MuJoCo one) of draws
/// 1..draw_count(), each printed.
std::vector<EpisodeScore> run_draws(const RobotTask& task, const Genome& genome) {
  std::vector<EpisodeScore> scores;
  for (int d = 1; d <= draw_count(); ++d) {
    EpisodeScore s;
    const char* world = std::getenv("WALK_COMMAND_WORLD");
    const Status st = task.run_world(
        genome,
        task.world_options(world != nullptr ? std::atoi(world) : 0, static_cast<std::uint64_t>(d)),
        s);
    EXPECT_TRUE(st) << st.message();
    const CommandFigures f = figures_of<CommandFigures>(s);
    std::printf("draw %2d: f1 %.4f f2 %.2f g", d, s.objectives[0], s.objectives[1]);
    for (double g : s.constraints) std::printf(" %.3f", g);
    std::printf(" %s\n  ", task.type()->outcome_note(task.config(), s, s.sim_time_s).c_str());
    for (const CommandSegmentFigures& seg : f.segments) {
      if (!seg.measured)
        std::printf("%s (not reached) ", seg.name.c_str());
      else if (seg.stand)
        std::printf("%s %s ", seg.name.c_str(), seg.stood ? "stood" : "did not stand");
      else
        std::printf("%s %.3f ", seg.name.c_str(), seg.speed);
    }
    std::printf("\n");
    scores.push_back(std::move(s));
  }
  return scores;
}

struct Spread {
  double median, q1, q3;
};
Spread spread(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  auto at = [&](double p) {
    const double i = p * static_cast<double>(v.size() - 1);
    const auto lo = static_cast<std::size_t>(i);
    const std::size_t hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (i - static_cast<double>(lo)) * (v[hi] - v[lo]);
  };
  return {at(0.5), at(0.25), at(0.75)};
}

/// A segment's figure over the draws, printed with its spread.
Spread segment_spread(const std::vector<EpisodeScore>& scores, const std::string& name,
                      double CommandSegmentFigures::*figure) {
  std::vector<double> v;
  for (const EpisodeScore& s : scores)
    for (const CommandSegmentFigures& seg : figures_of<CommandFigures>(s).segments)
      if (seg.name == name) v.push_back(seg.*figure);
  const Spread p = spread(v);
  std::printf("%-10s median %.3f, quartiles %.3f..%.3f over %zu draws\n", name.c_str(), p.median,
              p.q1, p.q3, v.size());
  return p;
}

// walk-command.json is the schedule (43.5 s, the stop's 1.5 s included) on the spline
// walk, and every gene starts at the firmware's default within the store's range.
TEST(WalkCommandTask, TheConfigRunsTheScheduleOnTheSplineWalkFromTheDefaults) {
  const TaskConfig c = command_config();
  const CommandSettings& settings = c.own_settings<CommandSettings>();
  EXPECT_EQ(settings.schedule, CommandSchedule{});
  EXPECT_DOUBLE_EQ(settings.schedule.total_s(), 43.5);
  EXPECT_EQ(settings.straightness, StraightnessLimits{});
  ASSERT_EQ(c.base_params.size(), 1u);
  EXPECT_EQ(c.base_params[0].first, "walk.engine");
  EXPECT_EQ(c.base_params[0].second, 1.0);
  EXPECT_EQ(c.world_count(), 2);  // one trial on each engine
  std::unique_ptr<fw::Firmware> firmware;
  ASSERT_TRUE(fw::Firmware::create({}, firmware));
  ASSERT_EQ(c.genes.size(), 40u);
  for (const TaskGene& g : c.genes) {
    const auto h = firmware->params().find(g.parameter);
    ASSERT_TRUE(h) << g.parameter;
    const fw::ParamSpec& spec = firmware->params().spec(*h);
    EXPECT_EQ(g.start, spec.default_value) << g.parameter;
    EXPECT_GE(g.min, spec.min) << g.parameter;
    EXPECT_LE(g.max, spec.max) << g.parameter;
  }
  // The run.json record reads back as the same settings.
  nlohmann::json doc;
  find_task_type(c.task)->write_settings(c, doc);
  CommandSchedule again;
  ASSERT_TRUE(parse_command_schedule(doc["command"], again));
  EXPECT_EQ(again, settings.schedule);
}

// The spline walk's defaults (firmware/include/stride/firmware/walk/spline_walk_parameters.hpp)
// walk every segment of the schedule in the drawn worlds: each direction's speed is positive the
// commanded way, the stop ends standing, and the speed objective is the mean of the capped
// ratios to the reference speeds.
TEST(WalkCommandTask, TheSplineWalksDefaultsScoreEverySegment) {
  const TaskConfig c = command_config();
  const RobotTask task(c);
  ASSERT_TRUE(task.check());
  const std::vector<EpisodeScore> scores = run_draws(task, task.start_genome());
  int falls = 0, stood = 0;
  for (const EpisodeScore& s : scores) {
    ASSERT_EQ(s.objectives.size(), 2u);
    ASSERT_EQ(s.constraints.size(), 5u);
    EXPECT_EQ(s.objectives[1], s.max_accel);
    const CommandFigures f = figures_of<CommandFigures>(s);
    double ratios = 0.0;
    for (int d = 0; d < kOmniSegments; ++d)
      ratios += std::min(1.5, f.directions[d].speed / kReferenceSpeeds[d]);
    EXPECT_NEAR(s.objectives[0], -ratios / kOmniSegments, 1e-12);
    falls += s.fell ? 1 : 0;
    for (const CommandSegmentFigures& seg : f.segments) stood += seg.stand && seg.stood ? 1 : 0;
  }
  std::printf("falls %d, stops that stood %d, of %zu draws\n", falls, stood, scores.size());
  // Measured 2026-11-28 over draws 1..20 (Simbody; the figures printed above): no fall, every
  // stop stood. Judged: at most 1 fall and at least 4 stops standing of 5, one to spare.
  EXPECT_LE(falls, 1);
  EXPECT_GE(stood, static_cast<int>(scores.size()) - 1);
  // Each segment's median speed over the draws against its 20-draw median less the larger of
  // 3 IQR and 10 % (median, quartiles over draws 1..20; m/s, turns rad/s):
  //   forward    0.248 (0.244..0.255)  limit 0.215     backward  0.181 (0.169..0.200)  limit 0.088
  //   left       0.115 (0.105..0.118)  limit 0.076     right     0.114 (0.104..0.119)  limit 0.069
  //   turn_left  0.672 (0.573..0.690)  limit 0.321     turn_right 0.640 (0.624..0.670) limit 0.502
  //   curve      0.208 (0.206..0.216)  limit 0.178     diagonal  0.181 (0.176..0.185)  limit 0.154
  //   restart    0.166 (0.161..0.173)  limit 0.130     reverse   0.182 (0.175..0.201)  limit 0.104
  //   the curve's turn rate 0.220 rad/s (0.205..0.254) limit 0.073.
  // Each is positive the commanded way (the diagonal along the direction the defaults plan).
  // On MuJoCo the same draws fall in 6 of 20 (3 starting forward at 4.5-5.3 s, 2 in the curve,
  // 1 in the restart; WALK_COMMAND_WORLD=1): that is the search's to fix, not asserted here.
  const std::vector<std::pair<std::string, double>> limits = {
      {"forward", 0.215},   {"backward", 0.088},   {"left", 0.076},  {"right", 0.069},
      {"turn_left", 0.321}, {"turn_right", 0.502}, {"curve", 0.178}, {"diagonal", 0.154},
      {"restart", 0.130},   {"reverse", 0.104}};
  for (const auto& [name, limit] : limits)
    EXPECT_GT(segment_spread(scores, name, &CommandSegmentFigures::speed).median, limit) << name;
  EXPECT_GT(segment_spread(scores, "curve", &CommandSegmentFigures::turn_rate_radps).median, 0.073);
}

// The legs at the weakest servo gain the genome allows (walk.spline.gains.legs 5 of 5..100)
// cannot carry the walk: the robot falls, which makes it infeasible, and every segment it did
// not reach counts as violated in each of its constraints and scores speed 0, so that it scores
// lower than the defaults in the same worlds.
TEST(WalkCommandTask, AGenomeThatFallsIsInfeasibleAndScoresLower) {
  const TaskConfig c = command_config();
  const RobotTask task(c);
  Genome weak = task.start_genome();
  for (std::size_t i = 0; i < c.genes.size(); ++i)
    if (c.genes[i].parameter == "walk.spline.gains.legs") weak.reals[i] = c.genes[i].min;
  const std::vector<EpisodeScore> fallen = run_draws(task, weak);
  const std::vector<EpisodeScore> defaults = run_draws(task, task.start_genome());
  const CommandSchedule& schedule = c.own_settings<CommandSettings>().schedule;
  int falls = 0, lower = 0;
  for (std::size_t d = 0; d < fallen.size(); ++d) {
    const EpisodeScore& s = fallen[d];
    lower += s.objectives[0] > defaults[d].objectives[0] ? 1 : 0;
    if (!s.fell) continue;
    ++falls;
    EXPECT_LT(s.constraints[0], -1.0);
    EXPECT_NE(task.type()->outcome_note(c, s, s.sim_time_s).find("fell at"), std::string::npos);
    // Each segment not reached adds -1 to every constraint it has.
    const CommandFigures f = figures_of<CommandFigures>(s);
    double translations = 0, turns = 0, stops = 0;
    for (std::size_t k = 0; k < f.segments.size(); ++k) {
      if (f.segments[k].measured) continue;
      const CommandSegmentSpec& spec = schedule.segments[k];
      const bool moves = spec.command[0] != 0.0 || spec.command[1] != 0.0;
      stops += spec.stand ? 1 : 0;
      translations += !spec.stand && spec.command[2] == 0.0 ? 1 : 0;
      turns += !spec.stand && !moves ? 1 : 0;
      EXPECT_EQ(f.segments[k].speed, 0.0) << f.segments[k].name;
    }
    EXPECT_LE(s.constraints[1], -translations);
    EXPECT_LE(s.constraints[2], -translations);
    EXPECT_LE(s.constraints[3], -turns);
    EXPECT_LE(s.constraints[4], -stops);
  }
  std::printf("falls %d, scores lower than the defaults %d, of %zu draws\n", falls, lower,
              fallen.size());
  // Measured 2026-11-28 over draws 1..20: 20 of 20 fell (16 in the forward segment at 4.8-6.0 s,
  // 4 in the backward one at 6.3-8.4 s), 20 of 20 scored lower than the defaults (f1 -0.049..0
  // against -0.473..-0.404). Judged: at least 4 of 5, one to spare.
  EXPECT_GE(falls, static_cast<int>(fallen.size()) - 1);
  EXPECT_GE(lower, static_cast<int>(fallen.size()) - 1);
}

// A bad schedule is one error naming the field; a schedule without one of the six directions
// the speed objective scores is refused naming it.
TEST(WalkCommandTask, ABadSettingNamesItsField) {
  auto error = [](const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json doc = command_doc();
    change(doc);
    TaskConfig c;
    const Status s = parse_task_config(doc, c);
    EXPECT_FALSE(s);
    return s.message();
  };
  auto has = [](const std::string& message, const std::string& what) {
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };
  has(error([](auto& d) {
        d["command"]["segments"][2]["command"] = {0.0, 2.0, 0.0};
      }),
      "command.segments[2].command: must be [vx, vy, vtheta], each in [-1, 1]");
  has(error([](auto& d) { d["command"]["measure_s"] = 5.0; }),
      "command.measure_s: must be in (0, hold_s]");
  has(error([](auto& d) { d["command"]["hold"] = 5.0; }), "command.hold: unknown field");
  has(error([](auto& d) { d["command"]["segments"][8]["speed"] = 1; }),
      "command.segments[8].speed: unknown field");
  has(error([](auto& d) { d["command"]["segments"][9]["name"] = "forward"; }),
      "command.segments[9].name: 'forward' appears twice");
  has(error([](auto& d) { d["command"]["segments"].erase(4); }),
      "command.segments: needs a segment named 'turn_left'");
  has(error([](auto& d) {
        d["command"]["segments"][1]["command"] = {-1.0, 0.2, 0.0};
      }),
      "command.segments[1].command: 'backward' must command that direction alone");
  has(error([](auto& d) {
        d["command"]["segments"][6]["command"] = {0.0, 0.0, 0.0};
      }),
      "command.segments[6].command: must not be zero");
  has(error([](auto& d) { d["max_drift_ratio"] = -1; }), "max_drift_ratio: must be >= 0");
  has(error([](auto& d) { d["task"] = "walk-commands"; }), "walk-command");
}

// A short run (pop 4, 2 generations, a 10.5 s schedule) completes on both engines, a run of
// one generation resumed to two gives the uninterrupted run's files, and its validation holds
// the task's speeds and segment figures.
TEST(WalkCommandTask, AShortRunCompletesResumesAndValidates) {
  test::TempDir tmp;
  nlohmann::json doc = command_doc();
  doc["pop"] = 4;
  doc["generations"] = 2;
  doc["pm"] = 0.2;
  doc["command"]["start_s"] = 0.5;
  doc["command"]["hold_s"] = 1.0;
  doc["command"]["measure_s"] = 0.5;
  doc["command"]["stop_s"] = 0.5;
  doc["validate"] = {{"seeds", 1}};
  const fs::path config = tmp.path() / "short.json";
  std::ofstream(config) << doc.dump(1);
  const std::string stride = kBin + "/stride";
  const std::string whole = (tmp.path() / "whole").string(), cut = (tmp.path() / "cut").string();
  auto run = [&](const std::vector<std::string>& args) {
    std::vector<std::string> argv = {stride};
    argv.insert(argv.end(), args.begin(), args.end());
    const test::ChildRun r = test::run_child(argv, tmp.path());
    EXPECT_EQ(r.code, 0) << r.err;
    return r;
  };
  run({"optimise", "--config", config.string(), "--out", whole, "--jobs", "2", "--no-validate"});
  run({"optimise", "--config", config.string(), "--out", cut, "--jobs", "2", "--generations", "1",
       "--no-validate"});
  run({"optimise", "--out", cut, "--resume", "--generations", "2", "--no-validate"});
  for (const char* f : {"evaluations.jsonl", "pareto.csv", "front-rescored.json"})
    EXPECT_EQ(test::read_file(fs::path(whole) / f), test::read_file(fs::path(cut) / f)) << f;
  const nlohmann::json run_json =
      nlohmann::json::parse(test::read_file(fs::path(whole) / "run.json"));
  EXPECT_EQ(run_json["task"]["command"]["hold_s"], 1.0);
  EXPECT_EQ(run_json["task"]["command"]["segments"].size(), 11u);
  // stride validate prints the direction table beside the reference figures and writes the
  // task's figures per world into validation.json.
  const test::ChildRun printed = run({"validate", whole, "--seeds", "1", "--jobs", "2"});
  EXPECT_NE(printed.out.find("speeds per direction"), std::string::npos) << printed.out;
  EXPECT_NE(printed.out.find("Bit-Bots NUgus (sim)"), std::string::npos) << printed.out;
  const nlohmann::json v =
      nlohmann::json::parse(test::read_file(fs::path(whole) / "validation.json"));
  EXPECT_EQ(v["task"], "walk-command");
  int cells = 0;
  for (const auto& individual : v["individuals"])
    for (const auto& cell : individual["worlds"]) {
      if (cell.contains("unavailable")) continue;
      ++cells;
      EXPECT_TRUE(cell["speeds"].contains("turn_right")) << cell.dump();
      ASSERT_EQ(cell["segments"].size(), 11u) << cell.dump();
      EXPECT_EQ(cell["segments"][8]["name"], "stop");
      EXPECT_TRUE(cell["segments"][8].contains("stood"));
      EXPECT_TRUE(cell["segments"][6].contains("turn_rate_radps"));
    }
  EXPECT_GT(cells, 0);
}

}  // namespace
}  // namespace stride::opt
