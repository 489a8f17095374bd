// The run directory: files written, refusal to overwrite, resume after an interruption (with a
// torn last line) reproducing the uninterrupted run's files.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "read_file.hpp"
#include "stride/optimiser/problems/test_problems.hpp"
#include "stride/optimiser/run/optimisation_run.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

namespace fs = std::filesystem;

/// The text with every `,"wall_s":<number>` removed (the only non-deterministic field).
std::string without_wall_time(std::string text) {
  const std::string key = ",\"wall_s\":";
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at)) {
    text.erase(at, text.find('}', at) - at);
  }
  return text;
}

RunConfig config(const std::string& problem) {
  RunConfig c;
  c.problem = problem;
  c.settings.seed = 4;
  c.settings.pop_size = 16;
  c.settings.generations = 6;
  c.settings.real_mut_prob = 0.5;
  return c;
}

struct Interrupt {};

TEST(RunDirectory, WritesEveryFile) {
  test::TempDir tmp;
  const auto problem = make_test_problem("bnh");
  SerialEvaluator evaluator;
  RunOptions options;
  options.dir = tmp.path() / "run";
  int calls = 0;
  options.on_generation = [&](const GenerationRecord& r) { EXPECT_EQ(r.generation, ++calls); };
  RunSummary summary;
  ASSERT_TRUE(run_optimisation(*problem, config("bnh"), evaluator, options, summary).is_ok());
  EXPECT_EQ(calls, 6);
  for (const char* f :
       {"run.json", "evaluations.jsonl", "generations.jsonl", "checkpoint.json", "pareto.csv"}) {
    EXPECT_TRUE(fs::exists(options.dir / f)) << f;
  }
  const std::string evaluations = test::read_file(options.dir / "evaluations.jsonl");
  EXPECT_EQ(static_cast<std::uint64_t>(std::count(evaluations.begin(), evaluations.end(), '\n')),
            summary.last.evaluations);
  const std::string generations = test::read_file(options.dir / "generations.jsonl");
  EXPECT_EQ(std::count(generations.begin(), generations.end(), '\n'), 6);
  EXPECT_NE(generations.find("\"hypervolume\":"), std::string::npos);
  EXPECT_NE(generations.find("\"igd\":"), std::string::npos);
  const std::string csv = test::read_file(options.dir / "pareto.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "f1,f2,x1,x2");
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')),
            summary.pareto_size + 1);
  const auto run = nlohmann::json::parse(test::read_file(options.dir / "run.json"));
  EXPECT_EQ(run["problem"], "bnh");
  EXPECT_EQ(run["settings"]["popSize"], 16);

  // A second run into the same directory is refused and changes nothing.
  const std::string before = test::read_file(options.dir / "checkpoint.json");
  RunSummary again;
  const Status st = run_optimisation(*problem, config("bnh"), evaluator, options, again);
  ASSERT_FALSE(st.is_ok());
  EXPECT_NE(st.message().find("already holds a run"), std::string::npos);
  EXPECT_EQ(test::read_file(options.dir / "checkpoint.json"), before);

  // Resuming with other settings is refused.
  RunConfig other = config("bnh");
  other.settings.seed = 5;
  options.resume = true;
  EXPECT_FALSE(run_optimisation(*problem, other, evaluator, options, again).is_ok());
  // Resuming a finished run changes nothing.
  ASSERT_TRUE(run_optimisation(*problem, config("bnh"), evaluator, options, again).is_ok());
  EXPECT_EQ(test::read_file(options.dir / "checkpoint.json"), before);
  EXPECT_EQ(again.last.evaluations, summary.last.evaluations);
}

TEST(RunDirectory, ResumeAfterAnInterruptionReproducesTheUninterruptedRun) {
  test::TempDir tmp;
  const auto problem = make_test_problem("zdt1");
  SerialEvaluator serial;
  RunOptions full;
  full.dir = tmp.path() / "full";
  RunSummary summary;
  ASSERT_TRUE(run_optimisation(*problem, config("zdt1"), serial, full, summary).is_ok());

  for (const int stop : {1, 4}) {
    RunOptions cut;
    cut.dir = tmp.path() / ("cut" + std::to_string(stop));
    cut.on_generation = [stop](const GenerationRecord& r) {
      if (r.generation == stop) throw Interrupt{};
    };
    EXPECT_THROW((void)run_optimisation(*problem, config("zdt1"), serial, cut, summary), Interrupt);
    // Work of the next generation that the checkpoint does not cover, and a torn line.
    {
      std::ofstream log(cut.dir / "evaluations.jsonl", std::ios::app);
      log << "{\"id\":999,\"generation\":9,\"reals\":[0.5]}\n{\"id\":1000,\"gen";
      std::ofstream gen(cut.dir / "generations.jsonl", std::ios::app);
      gen << "{\"generation\":";
    }
    cut.on_generation = nullptr;
    cut.resume = true;
    ThreadPoolEvaluator threads(3);  // another thread count must not matter either
    ASSERT_TRUE(run_optimisation(*problem, config("zdt1"), threads, cut, summary).is_ok());
    EXPECT_TRUE(summary.resumed);
    EXPECT_EQ(summary.resumed_at_generation, stop);
    for (const char* f : {"run.json", "evaluations.jsonl", "checkpoint.json", "pareto.csv"}) {
      EXPECT_EQ(test::read_file(cut.dir / f), test::read_file(full.dir / f))
          << f << " after stop " << stop;
    }
    EXPECT_EQ(without_wall_time(test::read_file(cut.dir / "generations.jsonl")),
              without_wall_time(test::read_file(full.dir / "generations.jsonl")));
  }
}

TEST(RunDirectory, DamagedCheckpointIsAClearError) {
  test::TempDir tmp;
  const auto problem = make_test_problem("zdt2");
  SerialEvaluator serial;
  RunOptions options;
  options.dir = tmp.path();
  RunSummary summary;
  ASSERT_TRUE(run_optimisation(*problem, config("zdt2"), serial, options, summary).is_ok());
  tmp.write("checkpoint.json",
            "{\"engine\": {\"format\": \"x\"}, \"run\": {\"evaluation_lines\": 3, "
            "\"generation_lines\": 1}}");
  options.resume = true;
  const Status st = run_optimisation(*problem, config("zdt2"), serial, options, summary);
  ASSERT_FALSE(st.is_ok());
  EXPECT_NE(st.message().find("checkpoint"), std::string::npos) << st.message();
  tmp.write("checkpoint.json", "{not json");
  EXPECT_FALSE(run_optimisation(*problem, config("zdt2"), serial, options, summary).is_ok());
}

}  // namespace
}  // namespace stride::opt
