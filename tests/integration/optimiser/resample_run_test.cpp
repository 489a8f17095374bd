// Trials that do not overfit (issue 41 point 2) end to end: a robot run whose trial worlds are
// drawn again each generation (config `resample`), seeded with several starts (`starts`),
// whose final front is scored again on fresh worlds (front-rescored.json) and whose picks
// come from those scores; the same files for any thread count, on MPI ranks and after an
// extension.
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "read_file.hpp"
#include "stride/optimiser/report/run_data.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

namespace fs = std::filesystem;
const std::string kBin = std::string(STRIDE_BIN_DIR);
const std::string kConfigs = std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/";

/// `stride args...` with its output in dir/stdout and dir/stderr; the exit code.
int stride(const std::vector<std::string>& args, const fs::path& dir) {
  std::string command = kBin + "/stride";
  for (const std::string& a : args) command += " '" + a + "'";
  command += " >" + (dir / "stdout").string() + " 2>" + (dir / "stderr").string();
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The seed's walk task, short (2 s, 0.3 m), on two randomised trial worlds with noise, drawn
/// again each generation, with the firmware defaults and a slower step as further starts.
nlohmann::json resampling_walk(int generations) {
  std::ifstream in(kConfigs + "walk.json");
  nlohmann::json c = nlohmann::json::parse(in);
  c["pop"] = 4;
  c["generations"] = generations;
  c["duration_s"] = 2.0;
  c["goal_distance_m"] = 0.3;
  c["pm"] = 0.2;
  c["trials"] = 2;
  c["randomisation"] = {{"imu_noise", true}, {"friction_range", 0.2}};
  c["resample"] = true;
  c["starts"] = {"defaults", {{"walk.walk_cycle.step_time", 0.95}, {"not.a.gene", 1.0}}};
  c["validate"] = {{"seeds", 2}};
  return c;
}

/// The same on three MPI ranks (`mpirun -n 3 stride ... --mpi`).
int stride_on_mpi_ranks(std::vector<std::string> args, const fs::path& dir) {
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  std::string command = "mpirun --oversubscribe -n 3";
  if (::geteuid() == 0) command += " --allow-run-as-root";
  command += " " + kBin + "/stride";
  args.push_back("--mpi");
  for (const std::string& a : args) command += " '" + a + "'";
  command += " >" + (dir / "stdout").string() + " 2>" + (dir / "stderr").string();
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

fs::path write(const fs::path& path, const nlohmann::json& doc) {
  std::ofstream(path) << doc.dump(1);
  return path;
}

TEST(ResampleRun, EachDrawHasItsOwnTrialWorldsAndDrawZeroIsTheFixedTrials) {
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(resampling_walk(2), c)) << "config";
  const RobotTask task(c);
  EXPECT_EQ(task.world_options(1, 0).seed, c.trial_seed + 1);
  EXPECT_EQ(task.world_options(1, 3).seed, c.trial_seed + 3 * kDrawSeedSpacing + 1);
  const Genome g = task.start_genome();
  const EvaluationOutcome fixed = task.evaluate(g);
  const EvaluationOutcome zero = task.evaluate_on(g, 0);
  const EvaluationOutcome other = task.evaluate_on(g, 1);
  ASSERT_FALSE(fixed.failed) << fixed.reason;
  ASSERT_FALSE(other.failed) << other.reason;
  EXPECT_EQ(fixed.objectives, zero.objectives);
  EXPECT_NE(fixed.objectives, other.objectives);                   // other worlds, other noise
  EXPECT_EQ(task.evaluate_on(g, 1).objectives, other.objectives);  // and repeatable

  // The starts: the registered defaults, and Ind_O with the one gene the object names.
  std::vector<Genome> starts;
  ASSERT_TRUE(task.extra_start_genomes(starts));
  ASSERT_EQ(starts.size(), 2u);
  EXPECT_EQ(starts[0], g);  // the walk's defaults are Ind_O
  std::size_t differ = 0;
  for (std::size_t i = 0; i < g.reals.size(); ++i) differ += starts[1].reals[i] != g.reals[i];
  EXPECT_EQ(differ, 1u);
}

TEST(ResampleRun, ThreadsMpiAndAnExtensionGiveTheSameFilesAndThePicksComeFromTheFreshScores) {
  test::TempDir tmp;
  const fs::path config = write(tmp.path() / "walk.json", resampling_walk(3));
  const fs::path two = write(tmp.path() / "walk-2.json", resampling_walk(2));
  const auto out = [&](const char* name) { return (tmp.path() / name).string(); };
  ASSERT_EQ(stride({"optimise", "--config", config.string(), "--out", out("serial"), "--jobs", "1",
                    "--no-validate"},
                   tmp.path()),
            0)
      << test::read_file(tmp.path() / "stderr");
  EXPECT_NE(test::read_file(tmp.path() / "stderr").find("scoring the final front again"),
            std::string::npos);
  ASSERT_EQ(stride({"optimise", "--config", config.string(), "--out", out("threads"), "--jobs", "2",
                    "--no-validate"},
                   tmp.path()),
            0)
      << test::read_file(tmp.path() / "stderr");
  // Per-generation draws on MPI ranks: the ranks evaluate, the root draws (issue 55 point 3).
  ASSERT_EQ(stride_on_mpi_ranks(
                {"optimise", "--config", config.string(), "--out", out("mpi"), "--no-validate"},
                tmp.path()),
            0)
      << test::read_file(tmp.path() / "stderr");
  ASSERT_EQ(stride({"optimise", "--config", two.string(), "--out", out("extended"), "--jobs", "2",
                    "--no-validate"},
                   tmp.path()),
            0)
      << test::read_file(tmp.path() / "stderr");
  ASSERT_EQ(stride({"optimise", "--out", out("extended"), "--resume", "--generations", "3",
                    "--no-validate"},
                   tmp.path()),
            0)
      << test::read_file(tmp.path() / "stderr");
  for (const char* other : {"threads", "mpi", "extended"})
    for (const char* f : {"evaluations.jsonl", "pareto.csv", "front-rescored.json"})
      EXPECT_EQ(test::read_file(tmp.path() / "serial" / f), test::read_file(tmp.path() / other / f))
          << other << " " << f;

  // Generation 1 holds Ind_O and the starts; later generations 8 genomes each (4 children,
  // the 4 parents again).
  const nlohmann::json run = nlohmann::json::parse(test::read_file(tmp.path() / "serial/run.json"));
  ASSERT_EQ(run["extra_starts"].size(), 2u);
  EXPECT_EQ(run["settings"]["resample"], true);
  std::vector<int> per_generation(4, 0);
  std::ifstream log(tmp.path() / "serial/evaluations.jsonl");
  for (std::string line; std::getline(log, line);)
    ++per_generation[nlohmann::json::parse(line)["generation"].get<std::size_t>()];
  // Ind_O and the defaults are one genome, evaluated once.
  EXPECT_EQ(per_generation[1], 3);
  for (int g : {2, 3}) {
    EXPECT_GT(per_generation[g], 4) << "generation " << g;  // the parents again
    EXPECT_LE(per_generation[g], 8) << "generation " << g;
  }

  // Every pareto.csv row has its fresh score; the picks are rows feasible on fresh worlds.
  report::RunData data;
  ASSERT_TRUE(report::load_run_data(tmp.path() / "serial", data));
  ASSERT_FALSE(data.front.empty());
  for (const FrontMember& m : data.front) EXPECT_EQ(m.rescored.size(), 2u);
  const std::vector<report::RunPick> picks = report::run_picks(data);
  ASSERT_FALSE(picks.empty());
  bool any_feasible = false;
  for (const FrontMember& m : data.front) any_feasible = any_feasible || m.rescored_feasible;
  for (const report::RunPick& p : picks) {
    EXPECT_EQ(p.rescored, data.front[p.front_index].rescored);
    if (any_feasible) {
      EXPECT_TRUE(data.front[p.front_index].rescored_feasible) << p.label;
    }
  }
  // The fresh worlds are not the run's: a member scores differently there.
  bool moved = false;
  for (const FrontMember& m : data.front) moved = moved || m.rescored != m.objectives;
  EXPECT_TRUE(moved);
}

TEST(ResampleRun, BadResampleOrStartIsOneLineNamingIt) {
  test::TempDir tmp;
  nlohmann::json c = resampling_walk(2);
  c["resample"] = "yes";
  const fs::path bad = write(tmp.path() / "bad.json", c);
  EXPECT_EQ(stride({"optimise", "--config", bad.string(), "--out", (tmp.path() / "a").string()},
                   tmp.path()),
            2);
  EXPECT_NE(test::read_file(tmp.path() / "stderr").find("resample: must be true or false"),
            std::string::npos)
      << test::read_file(tmp.path() / "stderr");
  c = resampling_walk(2);
  c["starts"] = {{{"walk.walk_cycle.step_time", 9.0}}};
  write(bad, c);
  EXPECT_EQ(stride({"optimise", "--config", bad.string(), "--out", (tmp.path() / "b").string()},
                   tmp.path()),
            2);
  const std::string err = test::read_file(tmp.path() / "stderr");
  EXPECT_NE(err.find("starts[0]: walk.walk_cycle.step_time = 9"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(tmp.path() / "b" / "run.json"));
  c["starts"] = {"no-such-file.json"};
  write(bad, c);
  EXPECT_EQ(stride({"optimise", "--config", bad.string(), "--out", (tmp.path() / "c").string()},
                   tmp.path()),
            2);
  EXPECT_NE(test::read_file(tmp.path() / "stderr").find("starts[0]: cannot open"),
            std::string::npos)
      << test::read_file(tmp.path() / "stderr");
}

}  // namespace
}  // namespace stride::opt
