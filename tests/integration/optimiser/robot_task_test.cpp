// Robot tasks end to end (short episodes, small populations): the genome reaches the firmware,
// the kick scores, robust trials aggregate, serial = threads = MPI (3 ranks), Ctrl-C then
// --resume equals the uninterrupted run, front/ files load in stride-fw and stride sim, and
// stride report rebuilds the plots.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "read_file.hpp"
#include "seeds.hpp"
#include "stride/optimiser/tasks/direction_figures.hpp"
#include "stride/optimiser/tasks/kick_figures.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "stride/optimiser/tasks/walk_figures.hpp"
#include "stride/optimiser/tasks/walk_omni_settings.hpp"
#include "stride/optimiser/tasks/walk_settings.hpp"
#include "task_figures_of.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

namespace fs = std::filesystem;
const std::string kBin = std::string(STRIDE_BIN_DIR);
const std::string kConfigs = std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/";

std::string without_wall_time(std::string text) {
  const std::string key = ",\"wall_s\":";
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at))
    text.erase(at, text.find('}', at) - at);
  return text;
}

pid_t launch(const std::string& program, const std::vector<std::string>& args,
             const fs::path& log_dir) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int out = ::open((log_dir / "stdout").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open((log_dir / "stderr").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(out, 1);
    ::dup2(err, 2);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(program.c_str()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execvp(program.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

int wait_exit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

int run(const std::string& program, const std::vector<std::string>& args, const fs::path& log_dir) {
  return wait_exit(launch(program, args, log_dir));
}

/// The walk task with a short episode (2 s, goal 0.3 m) so that a run takes seconds.
fs::path short_walk_config(const fs::path& dir, int generations) {
  std::ifstream in(kConfigs + "walk.json");
  nlohmann::json c = nlohmann::json::parse(in);
  c["pop"] = 4;
  c["generations"] = generations;
  c["duration_s"] = 2.0;
  c["goal_distance_m"] = 0.3;
  c["pm"] = 0.2;
  c["validate"] = {{"seeds", 2}};  // the validation at the end of each run stays short
  const fs::path path = dir / "walk-short.json";
  std::ofstream(path) << c.dump(1);
  return path;
}

TaskConfig load(const std::string& name) {
  TaskConfig c;
  EXPECT_TRUE(load_task_config(kConfigs + name, c));
  return c;
}

TEST(RobotTask, TheGenomeIsFlashedIntoTheFirmware) {
  TaskConfig c = load("walk.json");
  c.duration_s = 2.0;
  const RobotTask task(c);
  EpisodeScore original, changed, again;
  ASSERT_TRUE(task.run_trial(task.start_genome(), 0, original));
  Genome g = task.start_genome();
  for (std::size_t i = 0; i < c.genes.size(); ++i)
    if (c.genes[i].parameter == "walk.stance.gains.legs") g.reals[i] = c.genes[i].max;
  ASSERT_TRUE(task.run_trial(g, 0, changed));
  ASSERT_TRUE(task.run_trial(task.start_genome(), 0, again));
  const double distance_m = figures_of<WalkFigures>(original).distance_m;
  EXPECT_NE(distance_m, figures_of<WalkFigures>(changed).distance_m);  // stiffer legs change it
  EXPECT_EQ(distance_m, figures_of<WalkFigures>(again).distance_m);    // and it is deterministic
  EXPECT_EQ(original.objectives, again.objectives);
  ASSERT_EQ(original.objectives.size(), 2u);
  ASSERT_EQ(original.constraints.size(), 3u);  // fell, lateral drift, heading change
  EXPECT_EQ(original.objectives[1], original.max_accel);
  EXPECT_GT(original.max_accel, 5.0);
}

// The thesis's world by name (issue 29 point 6): "world": "seed" with the firmware's walk
// defaults of then as base parameters (firmware/config/seed-walk.json) walks Ind_O as the
// seed's world did (2.5 m in about 27 s, noise off), slower than the faithful default world
// (about 19 s); a base parameter the firmware does not know is named.
TEST(RobotTask, TheSeedsWorldAndWalkByNameAndBaseParameters) {
  TaskConfig c = load("walk.json");
  const RobotTask faithful(c);
  EpisodeScore now, seed_world;
  ASSERT_TRUE(faithful.run_trial(faithful.start_genome(), 0, now));
  nlohmann::json doc = to_json(c);
  doc["world"] = "seed";
  doc.erase("servo_law");
  doc.erase("imu");
  doc.erase("contact");
  doc["params"] = STRIDE_SOURCE_DIR "/firmware/config/seed-walk.json";
  TaskConfig seed;
  ASSERT_TRUE(parse_task_config(doc, seed));
  const RobotTask thesis(seed);
  ASSERT_TRUE(thesis.run_trial(thesis.start_genome(), 0, seed_world));
  const double faithful_s = figures_of<WalkFigures>(now).time_to_goal_s;
  const double seed_s = figures_of<WalkFigures>(seed_world).time_to_goal_s;
  std::printf("  Ind_O to 2.5 m: faithful world %.2f s, seed world and walk %.2f s\n", faithful_s,
              seed_s);
  EXPECT_GT(faithful_s, 17.0);
  EXPECT_LT(faithful_s, 21.0);
  EXPECT_GT(seed_s, 25.0);
  EXPECT_LT(seed_s, 29.0);
  seed.base_params = {{"walk.no_such_gain", 1.0}};
  EpisodeScore bad;
  const Status s = RobotTask(seed).run_trial(RobotTask(seed).start_genome(), 0, bad);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message().rfind("params: ", 0), 0u) << s.message();
  EXPECT_NE(s.message().find("walk.no_such_gain"), std::string::npos) << s.message();
}

// The README demo (toolchain/demo.sh, walk-demo.json) must be able to say "reaches": its
// Ind_O reaches the 2.5 m goal within the time limit in the run's worlds, without a fall and
// within the straightness constraints, with a margin for the validation's noisier worlds. 5 of
// the config's drawn worlds, counted with one to spare below the shares measured, and the
// median time. A change of 1e-5
// in the firmware's compliance offsets broke the straightness of the one world this test judged
// before (tests/bench/RESULTS.md). Measured 2026-11-28, worlds 0-19: 20 of 20 reach the goal
// without a fall, median 19.42 s (IQR 0.23, 18.87-19.74), 15 of 20 within the straightness
// constraints (worlds 7, 9, 15, 16, 19 drift or turn beyond them: tests/bench/RESULTS.md).
TEST(RobotTask, TheDemoConfigsIndOReachesTheGoalInItsWorld) {
  TaskConfig c = load("walk-demo.json");
  EXPECT_EQ(c.own_settings<WalkSettings>().goal_distance_m, 2.5);
  c.trials = test::seed_count(5);
  const RobotTask task(c);
  int straight = 0;
  std::vector<double> times;
  for (int trial = 0; trial < c.trials; ++trial) {
    EpisodeScore s;
    ASSERT_TRUE(task.run_trial(task.start_genome(), trial, s));
    const WalkFigures walked = figures_of<WalkFigures>(s);
    std::printf("  trial %d: fell %d, %.3f m, time to goal %.2f s, constraints", trial,
                s.fell ? 1 : 0, walked.distance_m, walked.time_to_goal_s);
    bool feasible = true;
    for (double g : s.constraints) {
      std::printf(" %.4f", g);
      feasible = feasible && g >= 0.0;
    }
    std::printf("\n");
    if (walked.time_to_goal_s > 0.0) {
      EXPECT_EQ(s.objectives[0], walked.time_to_goal_s);
    }
    const bool reached = !s.fell && walked.time_to_goal_s > 0.0;
    straight += reached && feasible ? 1 : 0;
    times.push_back(reached ? walked.time_to_goal_s : 1e9);
  }
  const test::Figures time("time to 2.5 m [s]", {}, times);
  std::printf("  %s\n", time.summary().c_str());
  EXPECT_GE(time.count_at_most(c.duration_s), c.trials - 1) << "reached the goal, no fall";
  EXPECT_GE(straight, test::count_limit(15.0 / 20.0, c.trials)) << "within the constraints";
  EXPECT_LT(time.median(), 0.8 * c.duration_s);  // 20 % to spare: 19.42 s, IQR 0.23
}

TEST(RobotTask, KickEpisodeMovesTheBallAndScoresTheSeedsObjectives) {
  TaskConfig c = load("kick.json");
  c.duration_s = 5.0;
  const RobotTask task(c);
  EpisodeScore s;
  ASSERT_TRUE(task.run_trial(task.start_genome(), 0, s));
  ASSERT_EQ(s.objectives.size(), 2u);
  ASSERT_EQ(s.constraints.size(), 2u);
  const KickFigures kicked = figures_of<KickFigures>(s);
  if (!s.fell) {
    EXPECT_GT(kicked.ball_distance_m, 0.05);
    EXPECT_DOUBLE_EQ(s.objectives[0], kicked.max_fps);
    EXPECT_NEAR(s.objectives[1], 1.0 / std::clamp(kicked.ball_distance_m, 0.001, 10.0), 1e-12);
    EXPECT_EQ(s.constraints[0], 0.0);
  } else {
    EXPECT_EQ(s.objectives[0], 1000.0);
    EXPECT_EQ(s.constraints[0], -10.0);
  }
}

TEST(RobotTask, RobustTrialsAggregateByMeanOrWorst) {
  TaskConfig c = load("walk.json");
  c.duration_s = 1.5;
  c.trials = 2;
  c.aggregate = Aggregate::kMean;
  const RobotTask mean_task(c);
  c.aggregate = Aggregate::kWorst;
  const RobotTask worst_task(c);
  const Genome g = mean_task.start_genome();
  EpisodeScore t0, t1;
  ASSERT_TRUE(mean_task.run_trial(g, 0, t0));
  ASSERT_TRUE(mean_task.run_trial(g, 1, t1));
  EXPECT_NE(t0.max_accel, t1.max_accel);  // two different randomised worlds
  const EvaluationOutcome mean = mean_task.evaluate(g);
  const EvaluationOutcome worst = worst_task.evaluate(g);
  ASSERT_FALSE(mean.failed) << mean.reason;
  ASSERT_FALSE(worst.failed) << worst.reason;
  for (int m = 0; m < 2; ++m) {
    EXPECT_DOUBLE_EQ(mean.objectives[m], 0.5 * (t0.objectives[m] + t1.objectives[m]));
    EXPECT_DOUBLE_EQ(worst.objectives[m], std::max(t0.objectives[m], t1.objectives[m]));
  }
  EXPECT_DOUBLE_EQ(worst.constraints[0], std::min(t0.constraints[0], t1.constraints[0]));
  EXPECT_EQ(mean_task.evaluate(g).objectives, mean.objectives);  // seeded: repeatable
}

// `engines` lists the engines every trial runs on: trials x engines worlds, aggregated like trials.
TEST(RobotTask, TrialsOnTwoEnginesAggregateOverEveryWorld) {
  TaskConfig c = load("walk.json");
  c.duration_s = 1.0;
  c.trials = 1;
  c.engines = {sim::EngineKind::kSimbody, sim::EngineKind::kMujoco};
  const RobotTask task(c);
  EXPECT_EQ(task.world_options(0).engine, sim::EngineKind::kSimbody);
  EXPECT_EQ(task.world_options(1).engine, sim::EngineKind::kMujoco);
  EXPECT_EQ(task.world_options(0).seed, task.world_options(1).seed);
  const Genome g = task.start_genome();
  EpisodeScore w0, w1;
  ASSERT_TRUE(task.run_trial(g, 0, w0));
  ASSERT_TRUE(task.run_trial(g, 1, w1));
  const EvaluationOutcome mean = task.evaluate(g);
  ASSERT_FALSE(mean.failed) << mean.reason;
  for (int m = 0; m < 2; ++m)
    EXPECT_DOUBLE_EQ(mean.objectives[m], 0.5 * (w0.objectives[m] + w1.objectives[m]));
}

TEST(RobotTaskCli, SerialThreadsAndMpiGiveTheSameRunAndTheFrontLoads) {
  test::TempDir tmp;
  // Every genome scored on both engines (issue 21): the same run whatever the evaluator.
  fs::path config = short_walk_config(tmp.path(), 2);
  {
    nlohmann::json c = nlohmann::json::parse(test::read_file(config));
    c["engines"] = {"simbody", "mujoco"};
    std::ofstream(config) << c.dump(1);
  }
  const std::string stride = kBin + "/stride";
  auto args = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> a = {"optimise", "--config", config.string(), "--out",
                                  (tmp.path() / out).string()};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  ASSERT_EQ(run(stride, args("serial", {"--jobs", "1"}), tmp.path()), 0)
      << test::read_file(tmp.path() / "stderr");
  ASSERT_EQ(run(stride, args("threads", {"--jobs", "2"}), tmp.path()), 0)
      << test::read_file(tmp.path() / "stderr");
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  std::vector<std::string> mpi = {"--oversubscribe", "-n", "3", stride};
  if (::geteuid() == 0) mpi.insert(mpi.begin(), "--allow-run-as-root");
  for (const auto& a : args("mpi", {"--mpi"})) mpi.push_back(a);
  ASSERT_EQ(run("mpirun", mpi, tmp.path()), 0) << test::read_file(tmp.path() / "stderr");
  for (const char* other : {"threads", "mpi"}) {
    for (const char* f : {"evaluations.jsonl", "pareto.csv", "checkpoint.json"})
      EXPECT_EQ(test::read_file(tmp.path() / "serial" / f), test::read_file(tmp.path() / other / f))
          << other << " " << f;
    EXPECT_EQ(without_wall_time(test::read_file(tmp.path() / "serial/generations.jsonl")),
              without_wall_time(test::read_file(tmp.path() / other / "generations.jsonl")));
  }
  // front/ files are parameter files of the firmware.
  const fs::path member = tmp.path() / "serial/front/000.json";
  ASSERT_TRUE(fs::exists(member));
  EXPECT_EQ(nlohmann::json::parse(test::read_file(member)).size(), 46u);
  EXPECT_EQ(run(kBin + "/stride-fw", {"--hal", "sim", "--params", member.string(), "--ticks", "5"},
                tmp.path()),
            0)
      << test::read_file(tmp.path() / "stderr");
  EXPECT_EQ(
      run(stride,
          {"sim", "walk", "--params", member.string(), "--vx", "1", "--duration", "0.3", "--json"},
          tmp.path()),
      0)
      << test::read_file(tmp.path() / "stderr");
  // stride report rebuilds the plots and names the picks.
  fs::remove(tmp.path() / "serial/hypervolume.svg");
  ASSERT_EQ(run(stride, {"report", (tmp.path() / "serial").string(), "--json"}, tmp.path()), 0)
      << test::read_file(tmp.path() / "stderr");
  const auto summary = nlohmann::json::parse(test::read_file(tmp.path() / "stdout"));
  EXPECT_EQ(summary["task"], "walk");
  EXPECT_GE(summary["generations"].get<int>(), 1);
  EXPECT_EQ(summary["generations"], summary["generations_planned"]);  // finished
  EXPECT_TRUE(summary["ind_o"].is_object());
  for (const char* key : {"fastest", "most_stable", "knee"})
    EXPECT_TRUE(summary.contains(key)) << key;
  for (const char* svg : {"hypervolume.svg", "pareto_by_generation.svg"})
    EXPECT_EQ(test::read_file(tmp.path() / "serial" / svg).rfind("<svg", 0), 0u) << svg;
  EXPECT_EQ(run(stride, {"report", (tmp.path() / "nothing").string()}, tmp.path()), 2);
}

TEST(RobotTaskCli, CtrlCStopsAfterACheckpointAndResumeFinishesTheSameRun) {
  test::TempDir tmp;
  const fs::path config = short_walk_config(tmp.path(), 4);
  const std::string stride = kBin + "/stride";
  const fs::path ref = tmp.path() / "ref", cut = tmp.path() / "cut";
  ASSERT_EQ(
      run(stride, {"optimise", "--config", config.string(), "--out", ref.string(), "--jobs", "1"},
          tmp.path()),
      0)
      << test::read_file(tmp.path() / "stderr");
  const pid_t pid = launch(
      stride, {"optimise", "--config", config.string(), "--out", cut.string(), "--jobs", "1"},
      tmp.path());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  for (;;) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    try {
      const auto cp = nlohmann::json::parse(test::read_file(cut / "checkpoint.json"));
      if (cp["engine"]["completed_generations"].get<int>() >= 1) break;
    } catch (const nlohmann::json::exception&) {
    }
  }
  ASSERT_EQ(::kill(pid, SIGINT), 0);
  EXPECT_EQ(wait_exit(pid), 130);
  EXPECT_NE(test::read_file(tmp.path() / "stderr").find("--resume"), std::string::npos);
  const auto cp = nlohmann::json::parse(test::read_file(cut / "checkpoint.json"));
  const int done = cp["engine"]["completed_generations"].get<int>();
  EXPECT_LT(done, 4);
  // stride report on the stopped run says how far it got and how to go on.
  ASSERT_EQ(run(stride, {"report", cut.string()}, tmp.path()), 0)
      << test::read_file(tmp.path() / "stderr");
  EXPECT_NE(test::read_file(tmp.path() / "stdout")
                .find("walk run, generation " + std::to_string(done) + " of 4 (unfinished)"),
            std::string::npos)
      << test::read_file(tmp.path() / "stdout");
  EXPECT_NE(test::read_file(tmp.path() / "stderr")
                .find("unfinished: generation " + std::to_string(done) +
                      " of 4 (stride optimise "
                      "--out " +
                      cut.string() + " --resume continues it)"),
            std::string::npos)
      << test::read_file(tmp.path() / "stderr");
  ASSERT_EQ(run(stride, {"optimise", "--out", cut.string(), "--resume", "--jobs", "2"}, tmp.path()),
            0)
      << test::read_file(tmp.path() / "stderr");
  for (const char* f : {"run.json", "evaluations.jsonl", "checkpoint.json", "pareto.csv"})
    EXPECT_EQ(test::read_file(cut / f), test::read_file(ref / f)) << f;
}

/// walk-omni with short segments (start 4 s, ramp 0.5 s, hold 2 s, stop 0.5 s: 22 s).
fs::path short_omni_config(const fs::path& dir) {
  std::ifstream in(kConfigs + "walk-omni.json");
  nlohmann::json c = nlohmann::json::parse(in);
  c["pop"] = 4;
  c["generations"] = 1;
  c["pm"] = 0.2;
  c["trials"] = 1;
  c["omni"] = {{"start_s", 4.0}, {"ramp_s", 0.5}, {"hold_s", 2.0}, {"stop_s", 0.5}};
  c["validate"] = {{"seeds", 1}};
  const fs::path path = dir / "omni-short.json";
  std::ofstream(path) << c.dump(1);
  return path;
}

// Ind_O in walk-omni's drawn worlds at the task's trial step (5 trials; the segments shortened
// to a 1 s ramp, a 4 s hold and a 1 s stop): the score is the episode's own figures (Obj1 the
// Bit-Bots' combination of the segments' speeds, the constraints from the straightness limits),
// and Ind_O walks every segment without a fall (counted with one to spare), forward, backward
// the right way, and turning both ways (medians). Seed 1 of the nominal world at a 2 ms step
// and the full timing measured forward 0.168 m/s, backward 0.031, sideways about 0.01 and
// turning 0.19 rad/s; forward it turns 11 deg (over the 10 deg limit), sideways it drifts about
// 10 % and each turn translates 0.24-0.25 m (limit 0.1 m): Ind_O's known limits, in
// tests/bench/RESULTS.md, not asserted (tests/README.md, rule 4). Measured 2026-11-28, worlds
// 0-19: forward median 0.172 m/s (IQR 0.005), backward 0.0135 (IQR 0.0037), left 0.0095 and right
// 0.0090, turning left 0.191 rad/s (IQR 0.017) and right 0.195 (IQR 0.026); every segment measured
// and no fall in 20 of 20.
TEST(RobotTask, WalkOmniScoresEverySegmentOfIndO) {
  TaskConfig c = load("walk-omni.json");
  c.trials = test::seed_count(5);
  c.own_settings<OmniSettings>().timing = {4.0, 1.0, 4.0, 1.0};
  const RobotTask task(c);
  std::array<std::vector<double>, kOmniSegments> speeds;
  int walked = 0;
  for (int trial = 0; trial < c.trials; ++trial) {
    EpisodeScore a;
    ASSERT_TRUE(task.run_trial(task.start_genome(), trial, a));
    ASSERT_EQ(a.objectives.size(), 2u);
    ASSERT_EQ(a.constraints.size(), 4u);
    const OmniSegments segments = figures_of<DirectionFigures>(a).segments;
    bool all_measured = true;
    for (int k = 0; k < kOmniSegments; ++k) {
      const OmniSegment& s = segments[static_cast<std::size_t>(k)];
      std::printf(
          "  trial %d %-10s measured %d speed %+.4f drift %.3f heading %.2f deg "
          "translation %.3f m\n",
          trial, to_string(static_cast<OmniDirection>(k)), s.measured ? 1 : 0, s.speed,
          s.drift_ratio, s.heading_change_rad * 180.0 / 3.141592653589793, s.translation_m);
      speeds[static_cast<std::size_t>(k)].push_back(s.speed);
      all_measured = all_measured && s.measured;
    }
    std::printf("  objectives %.4f %.3f constraints %.4f %.4f %.4f %.4f fell %d\n", a.objectives[0],
                a.objectives[1], a.constraints[0], a.constraints[1], a.constraints[2],
                a.constraints[3], a.fell ? 1 : 0);
    EXPECT_DOUBLE_EQ(a.objectives[0], omni_speed_objective(segments));
    const auto c13 = omni_constraints(segments, c.own_settings<OmniSettings>().straightness);
    EXPECT_EQ(a.constraints[1], c13[0]);
    EXPECT_EQ(a.constraints[2], c13[1]);
    EXPECT_EQ(a.constraints[3], c13[2]);
    EXPECT_EQ(a.objectives[1], a.max_accel);
    EXPECT_EQ(a.constraints[0] == 0.0, !a.fell);
    walked += all_measured && !a.fell ? 1 : 0;
  }
  EXPECT_GE(walked, c.trials - 1) << "every segment measured, no fall";
  const auto median = [&](int k, const char* what) {
    const test::Figures f(what, {}, speeds[static_cast<std::size_t>(k)]);
    std::printf("  %s\n", f.summary().c_str());
    return f.median();
  };
  EXPECT_GT(median(0, "forward [m/s]"), 0.15);  // 0.172, IQR 0.005
  EXPECT_GT(median(1, "backward [m/s]"), 0.0);  // the right way: 0.0135, IQR 0.0037
  median(2, "left [m/s]");
  median(3, "right [m/s]");
  EXPECT_GT(median(4, "turn left [rad/s]"), 0.11);   // 0.191, IQR 0.017
  EXPECT_GT(median(5, "turn right [rad/s]"), 0.11);  // 0.195, IQR 0.026
}

// A tiny walk-omni run; `stride report` prints the per-direction table of Ind_O, the picks,
// each direction's best and the reference figures.
TEST(RobotTaskCli, WalkOmniRunReportsSpeedsPerDirection) {
  test::TempDir tmp;
  const fs::path config = short_omni_config(tmp.path());
  const std::string stride = kBin + "/stride";
  const fs::path out = tmp.path() / "omni";
  ASSERT_EQ(
      run(stride, {"optimise", "--config", config.string(), "--out", out.string(), "--jobs", "1"},
          tmp.path()),
      0)
      << test::read_file(tmp.path() / "stderr");
  ASSERT_EQ(run(stride, {"report", out.string(), "--json"}, tmp.path()), 0)
      << test::read_file(tmp.path() / "stderr");
  const auto summary = nlohmann::json::parse(test::read_file(tmp.path() / "stdout"));
  EXPECT_EQ(summary["task"], "walk-omni");
  ASSERT_TRUE(summary["directions"].is_array());
  std::vector<std::string> labels;
  for (const auto& row : summary["directions"]) labels.push_back(row["label"]);
  ASSERT_GE(labels.size(), 3u);
  EXPECT_EQ(labels.front(), "Ind_O");
  EXPECT_EQ(labels.back(), "Bit-Bots NUgus (sim)");
  EXPECT_EQ(labels[labels.size() - 2], "best per direction");
  EXPECT_NE(std::find(labels.begin(), labels.end(), "fastest"), labels.end());
  EXPECT_DOUBLE_EQ(summary["directions"].back()["speeds"]["turn_left"].get<double>(), 1.97);
  // The table's fastest member scores the run's best Obj1 again (same worlds, deterministic).
  for (const auto& row : summary["directions"]) {
    if (row["label"] != "fastest") continue;
    const auto& v = row["speeds"];
    const double obj1 = -(v["forward"].get<double>() + v["backward"].get<double>() +
                          v["left"].get<double>() + v["right"].get<double>() +
                          0.1 * (v["turn_left"].get<double>() + v["turn_right"].get<double>()));
    EXPECT_NEAR(obj1, summary["fastest"]["objectives"][0].get<double>(), 1e-12);
  }
  ASSERT_EQ(run(stride, {"report", out.string()}, tmp.path()), 0);
  const std::string text = test::read_file(tmp.path() / "stdout");
  EXPECT_NE(text.find("best per direction"), std::string::npos) << text;
  EXPECT_NE(text.find("Bit-Bots NUgus (sim)"), std::string::npos) << text;
  // The validation at the end of the run: per world, the speed table of Ind_O and the picks.
  EXPECT_NE(text.find("speeds per direction, world fresh seeds"), std::string::npos) << text;
  const auto validation = nlohmann::json::parse(test::read_file(out / "validation.json"));
  EXPECT_EQ(validation["task"], "walk-omni");
  for (const auto& ind : validation["individuals"])
    for (const auto& cell : ind["worlds"]) EXPECT_TRUE(cell["speeds"].contains("turn_right"));
}

TEST(RobotTaskCli, BadConfigNamesTheField) {
  test::TempDir tmp;
  std::ifstream in(kConfigs + "walk.json");
  nlohmann::json c = nlohmann::json::parse(in);
  c["genes"][2]["min"] = "low";
  std::ofstream(tmp.path() / "bad.json") << c.dump();
  EXPECT_EQ(run(kBin + "/stride",
                {"optimise", "--config", (tmp.path() / "bad.json").string(), "--out",
                 (tmp.path() / "run").string()},
                tmp.path()),
            2);
  const std::string err = test::read_file(tmp.path() / "stderr");
  EXPECT_NE(err.find("genes[2].min"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);
  EXPECT_FALSE(fs::exists(tmp.path() / "run"));
}

}  // namespace
}  // namespace stride::opt
