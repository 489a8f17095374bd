// `stride optimise` end to end: SIGKILL mid-generation and resume reproduces the uninterrupted
// run byte for byte; bad inputs exit 2 with one line; a small ZDT1 budget reaches a clear
// hypervolume; the constrained problems end on their known fronts.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "read_file.hpp"
#include "stride/optimiser/nsga2/evaluator.hpp"
#include "stride/optimiser/problems/test_problems.hpp"
#include "stride/optimiser/run/optimisation_run.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

namespace fs = std::filesystem;

const std::string kStride = std::string(STRIDE_BIN_DIR) + "/stride";

std::size_t count_lines(const fs::path& p) {
  const std::string text = test::read_file(p);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

/// checkpoint.json of a running optimisation, or nothing while it is not written yet.
std::optional<nlohmann::json> read_checkpoint(const fs::path& dir) {
  try {
    return nlohmann::json::parse(test::read_file(dir / "checkpoint.json"));
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

/// Starts `stride args...` with stdout/stderr sent to files in `log_dir`.
pid_t launch(const std::vector<std::string>& args, const fs::path& log_dir) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int out = ::open((log_dir / "stdout").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open((log_dir / "stderr").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(out, 1);
    ::dup2(err, 2);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(kStride.c_str()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(kStride.c_str(), argv.data());
    ::_exit(127);
  }
  return pid;
}

int wait_exit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

int run_stride(const std::vector<std::string>& args, const fs::path& log_dir) {
  return wait_exit(launch(args, log_dir));
}

/// The text with every `,"wall_s":<number>` removed (the only non-deterministic field).
std::string without_wall_time(std::string text) {
  const std::string key = ",\"wall_s\":";
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at)) {
    text.erase(at, text.find('}', at) - at);
  }
  return text;
}

TEST(OptimiseCli, ASecondInterruptStopsAtOnceAndResumeRedoesTheDroppedGeneration) {
  // The first SIGINT lets the generation in flight finish (it says so); a second one stops at
  // once with the last checkpoint intact, so --resume still gives the uninterrupted run.
  test::TempDir tmp;
  const std::vector<std::string> common = {"optimise",      "--problem", "zdt1",   "--pop", "20",
                                           "--generations", "6",         "--seed", "5"};
  const fs::path ref = tmp.path() / "ref", cut = tmp.path() / "cut";
  std::vector<std::string> args = common;
  args.insert(args.end(), {"--out", ref.string()});
  ASSERT_EQ(run_stride(args, tmp.path()), 0) << test::read_file(tmp.path() / "stderr");
  args = common;
  args.insert(args.end(), {"--out", cut.string(), "--slow-eval-ms", "50"});  // 1 s a generation
  const pid_t pid = launch(args, tmp.path());
  std::size_t logged = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  for (;;) {  // the first interrupt early in generation 2: at least 10 evaluations (0.5 s) left
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the run never got there";
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const std::optional<nlohmann::json> checkpoint = read_checkpoint(cut);
    if (!checkpoint) continue;
    const nlohmann::json& cp = *checkpoint;
    logged = cp["run"]["evaluation_lines"].get<std::size_t>();
    const std::size_t lines = count_lines(cut / "evaluations.jsonl");
    if (cp["engine"]["completed_generations"].get<int>() >= 1 && lines >= logged + 2 &&
        lines <= logged + 10) {
      ASSERT_EQ(::kill(pid, SIGINT), 0);
      break;
    }
  }
  while (test::read_file(tmp.path() / "stderr").find("stopping after the generation in flight") ==
         std::string::npos) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << test::read_file(tmp.path() / "stderr");
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_EQ(::kill(pid, SIGINT), 0);
  EXPECT_EQ(wait_exit(pid), 130);
  EXPECT_NE(test::read_file(tmp.path() / "stderr").find("stopped now"), std::string::npos);
  const auto cp = nlohmann::json::parse(test::read_file(cut / "checkpoint.json"));
  EXPECT_EQ(cp["run"]["evaluation_lines"].get<std::size_t>(), logged);  // generation 2 dropped
  EXPECT_GT(count_lines(cut / "evaluations.jsonl"), logged);            // stopped inside it
  ASSERT_EQ(run_stride({"optimise", "--out", cut.string(), "--resume"}, tmp.path()), 0)
      << test::read_file(tmp.path() / "stderr");
  for (const char* f : {"run.json", "evaluations.jsonl", "checkpoint.json", "pareto.csv"})
    EXPECT_EQ(test::read_file(cut / f), test::read_file(ref / f)) << f;
}

TEST(OptimiseCli, SigkillMidGenerationThenResumeReproducesTheUninterruptedRun) {
  test::TempDir tmp;
  const std::vector<std::string> common = {"optimise",      "--problem", "zdt1",   "--pop", "20",
                                           "--generations", "12",        "--seed", "3"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = common;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const fs::path ref = tmp.path() / "ref";
  ASSERT_EQ(run_stride(with({"--out", ref.string()}), tmp.path()), 0)
      << test::read_file(tmp.path() / "stderr");

  const fs::path cut = tmp.path() / "cut";
  int kills = 0;
  for (const std::size_t kill_at_generation : {3u, 7u}) {
    // Slow evaluations (3 ms each) so that the kill lands inside a generation.
    std::vector<std::string> args =
        kills == 0 ? with({"--out", cut.string(), "--slow-eval-ms", "3"})
                   : std::vector<std::string>{"optimise", "--out",          cut.string(),
                                              "--resume", "--slow-eval-ms", "3"};
    const pid_t pid = launch(args, tmp.path());
    std::size_t beyond = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    for (;;) {
      ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the run never got there";
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      const std::optional<nlohmann::json> checkpoint = read_checkpoint(cut);
      if (!checkpoint) continue;  // not written yet
      const nlohmann::json& cp = *checkpoint;
      const auto done = cp["engine"]["completed_generations"].get<std::size_t>();
      const auto logged = cp["run"]["evaluation_lines"].get<std::size_t>();
      const std::size_t lines = count_lines(cut / "evaluations.jsonl");
      if (done >= kill_at_generation && lines >= logged + 5) {
        ASSERT_EQ(::kill(pid, SIGKILL), 0);
        beyond = lines - logged;
        break;
      }
    }
    EXPECT_EQ(wait_exit(pid), -SIGKILL);
    EXPECT_GE(beyond, 5u);  // killed mid-generation: evaluations beyond the checkpoint
    ++kills;
  }
  // Finish with two evaluation threads: the thread count must not matter.
  ASSERT_EQ(run_stride({"optimise", "--out", cut.string(), "--resume", "--jobs", "2", "--json"},
                       tmp.path()),
            0)
      << test::read_file(tmp.path() / "stderr");
  const auto summary = nlohmann::json::parse(test::read_file(tmp.path() / "stdout"));
  EXPECT_TRUE(summary["resumed"].get<bool>());
  EXPECT_EQ(summary["generations"], 12);
  for (const char* f : {"run.json", "evaluations.jsonl", "checkpoint.json", "pareto.csv"}) {
    EXPECT_EQ(test::read_file(cut / f), test::read_file(ref / f)) << f;
  }
  EXPECT_EQ(without_wall_time(test::read_file(cut / "generations.jsonl")),
            without_wall_time(test::read_file(ref / "generations.jsonl")));
  EXPECT_EQ(count_lines(cut / "generations.jsonl"), 12u);
}

TEST(OptimiseCli, BadInputExitsTwoWithOneLineNamingIt) {
  test::TempDir tmp;
  const std::string out = (tmp.path() / "run").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"optimise", "--problem", "zdt1", "--pop", "10", "--out", out}, "multiple of 4"},
      {{"optimise", "--problem", "zdt9", "--out", out}, "zdt9"},
      {{"optimise", "--problem", "zdt1", "--pc", "2", "--out", out}, "realCrossProb"},
      {{"optimise", "--problem", "zdt1", "--etam", "-3", "--out", out}, "etaM"},
      {{"optimise", "--problem", "zdt1", "--generations", "abc", "--out", out}, "--generations"},
      {{"optimise", "--problem", "zdt1"}, "--out"},
      {{"optimise", "--problem", "zdt1", "--bogus", "--out", out}, "--bogus"},
      {{"optimise", "--out", out, "--resume"}, "run.json"},
      {{"optimise", "--problem", "bnh", "--start", "1,2,3", "--out", out}, "start"},
  };
  for (const auto& [args, word] : cases) {
    EXPECT_EQ(run_stride(args, tmp.path()), 2) << word;
    const std::string err = test::read_file(tmp.path() / "stderr");
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find(word), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(out)) << "bad input must not create the run directory";
  }
  ASSERT_EQ(
      run_stride({"optimise", "--problem", "bnh", "--pop", "8", "--generations", "2", "--out", out},
                 tmp.path()),
      0);
  EXPECT_EQ(run_stride({"optimise", "--problem", "bnh", "--out", out}, tmp.path()), 2);
  EXPECT_EQ(run_stride({"optimise", "--out", out, "--resume", "--pop", "12"}, tmp.path()), 2);
  EXPECT_EQ(run_stride({"optimise", "--help"}, tmp.path()), 0);
  EXPECT_NE(test::read_file(tmp.path() / "stdout").find("--etac"), std::string::npos);
}

// A finished run resumed with a larger --generations goes on exactly as a run started with
// that total: the same evaluations.jsonl, pareto.csv, run.json and checkpoint, byte for byte,
// whether extended in one step or two; a smaller total is refused, naming both.
TEST(OptimiseCli, ExtendingAFinishedRunEqualsRunningTheLongerOneFromTheStart) {
  test::TempDir tmp;
  for (const char* problem : {"zdt1", "osy"}) {
    const fs::path extended = tmp.path() / (std::string(problem) + "-extended");
    const fs::path direct = tmp.path() / (std::string(problem) + "-direct");
    const std::vector<std::string> common = {"optimise", "--problem", problem, "--pop",
                                             "12",       "--seed",    "7"};
    auto with = [&common](std::vector<std::string> more) {
      std::vector<std::string> args = common;
      args.insert(args.end(), more.begin(), more.end());
      return args;
    };
    ASSERT_EQ(run_stride(with({"--generations", "3", "--out", extended.string()}), tmp.path()), 0);
    ASSERT_EQ(run_stride({"optimise", "--out", extended.string(), "--resume", "--generations", "5"},
                         tmp.path()),
              0)
        << test::read_file(tmp.path() / "stderr");
    ASSERT_EQ(run_stride({"optimise", "--out", extended.string(), "--resume", "--generations", "8"},
                         tmp.path()),
              0);
    ASSERT_EQ(run_stride(with({"--generations", "8", "--out", direct.string()}), tmp.path()), 0);
    for (const char* file : {"evaluations.jsonl", "pareto.csv", "run.json", "checkpoint.json"})
      EXPECT_EQ(test::read_file(extended / file), test::read_file(direct / file))
          << problem << " " << file;
    EXPECT_EQ(without_wall_time(test::read_file(extended / "generations.jsonl")),
              without_wall_time(test::read_file(direct / "generations.jsonl")))
        << problem;
    EXPECT_EQ(run_stride({"optimise", "--out", extended.string(), "--resume", "--generations", "6"},
                         tmp.path()),
              2);
    EXPECT_EQ(test::read_file(tmp.path() / "stderr"),
              "stride optimise: --generations: 6 is below the run's 8 (--resume can only extend a "
              "run)\n");
  }
}

/// Runs NSGA-II in memory (no run directory) and returns the final indicators.
GenerationRecord solve(const std::string& name, std::uint64_t seed, int pop, int generations) {
  const auto problem = make_test_problem(name);
  Nsga2Settings s;
  s.seed = seed;
  s.pop_size = pop;
  s.generations = generations;
  s.real_mut_prob = 1.0 / static_cast<double>(problem->shape().reals.size());
  std::unique_ptr<Nsga2> engine;
  EXPECT_TRUE(Nsga2::create(s, problem->shape(), std::nullopt, engine).is_ok());
  while (!engine->finished()) {
    for (const Candidate& c : engine->ask()) {
      EXPECT_TRUE(engine->tell(c.id, problem->evaluate(c.genome)).is_ok());
    }
    EXPECT_TRUE(engine->advance().is_ok());
  }
  return measure(*problem, engine->population(), problem->reference());
}

TEST(OptimiseQuality, Zdt1SmallBudgetReachesNinetyFivePercentHypervolume) {
  // pop 100 x 100 generations (10,000 evaluations), three seeds; measured 96.7-97.0 %, a random
  // population is near 0 % and 250 generations reach 99.2 % (tests/bench/RESULTS.md).
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const GenerationRecord r = solve("zdt1", seed, 100, 100);
    ASSERT_TRUE(r.hypervolume_ratio.has_value());
    EXPECT_GE(*r.hypervolume_ratio, 0.95) << "seed " << seed;
    EXPECT_EQ(r.front_size, 100);
  }
}

TEST(OptimiseQuality, ConstrainedProblemsReachTheirKnownFronts) {
  for (const std::string name : {"bnh", "srn", "tnk", "osy"}) {
    const GenerationRecord r = solve(name, 1, 100, 250);
    EXPECT_EQ(r.feasible, 100) << name;
    ASSERT_TRUE(r.igd.has_value());
    EXPECT_LT(*r.igd, 0.04) << name;  // normalised objectives; OSY is the hardest (~0.03)
    EXPECT_GE(*r.hypervolume_ratio, 0.97) << name;
  }
}

}  // namespace
}  // namespace stride::opt
