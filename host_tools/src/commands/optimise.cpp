// `stride optimise`: runs NSGA-II on a problem and writes a run directory (optimiser/README.md).
//
// The problem is a test problem (--problem NAME) or a robot task (--config FILE: walk, walk-omni or
// kick, optimiser/configs/). Robot runs also get front/ parameter files and SVG plots (run_report).
// On a terminal a progress bar is drawn; Ctrl-C stops after the next checkpoint.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "stride/core/cli_args.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/optimiser/nsga2/evaluator.hpp"
#include "stride/optimiser/nsga2/mpi_evaluator.hpp"
#include "stride/optimiser/problems/test_problems.hpp"
#include "stride/optimiser/report/run_plots.hpp"
#include "stride/optimiser/run/optimisation_run.hpp"
#include "stride/optimiser/run/progress.hpp"
#include "stride/optimiser/run/run_report.hpp"
#include "stride/optimiser/run/validation.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"
#include "stride/sim_hal/sim_cli.hpp"

namespace {

using stride::Status;
namespace opt = stride::opt;

/// Wraps a problem so that each evaluation takes at least `delay` (to test interruption).
class SlowProblem final : public opt::Problem {
 public:
  SlowProblem(std::unique_ptr<opt::Problem> inner, std::chrono::milliseconds delay)
      : inner_(std::move(inner)), delay_(delay) {}
  std::string name() const override { return inner_->name(); }
  const opt::ProblemShape& shape() const override { return inner_->shape(); }
  opt::EvaluationOutcome evaluate(const opt::Genome& genome) const override {
    std::this_thread::sleep_for(delay_);
    return inner_->evaluate(genome);
  }
  opt::EvaluationOutcome evaluate_on(const opt::Genome& genome, std::uint64_t draw) const override {
    std::this_thread::sleep_for(delay_);
    return inner_->evaluate_on(genome, draw);
  }
  std::optional<opt::FrontReference> reference() const override { return inner_->reference(); }

 private:
  std::unique_ptr<opt::Problem> inner_;
  std::chrono::milliseconds delay_;
};

std::atomic<bool> g_stop{false};
/// First SIGINT/SIGTERM: finish the generation in flight, checkpoint, exit 130. A second one
/// exits 130 at once: the last checkpoint stays, and --resume redoes the dropped generation
/// (files are replaced atomically and the logs cut back to the checkpoint, so nothing tears).
/// Only async-signal-safe calls here (write, _exit).
extern "C" void on_interrupt(int) {
  if (g_stop.exchange(true)) {
    constexpr char now[] =
        "\nstride optimise: stopped now; --resume redoes the unfinished generation\n";
    (void)!::write(STDERR_FILENO, now, sizeof now - 1);
    ::_exit(130);
  }
  constexpr char later[] =
      "\nstride optimise: stopping after the generation in flight (interrupt again to stop "
      "now)\n";
  (void)!::write(STDERR_FILENO, later, sizeof later - 1);
}

const stride::tools::CommandErrors errors("optimise");

std::string problem_list() {
  std::string names;
  for (const auto& n : opt::test_problem_names()) names += (names.empty() ? "" : "|") + n;
  return names;
}

/// The problem named on the command line (test problems today; tasks from --config later).
Status make_problem(const std::string& name, std::unique_ptr<opt::Problem>& out) {
  if (opt::find_task_type(name) != nullptr)
    return Status::error("task '" + name + "' needs --config FILE");
  out = opt::make_test_problem(name);
  if (!out) return Status::error("--problem '" + name + "' is not one of " + problem_list());
  return {};
}

Status parse_start(const std::string& text, opt::Genome& genome) {
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0') {
      return Status::error("--start: '" + item + "' is not a number");
    }
    genome.reals.push_back(v);
  }
  return {};
}

struct Settings {
  opt::RunConfig config;
  std::int64_t jobs = 1;
  std::int64_t slow_ms = 0;
};

Status read_int(const stride::core::CliArgs& args, const char* name, std::int64_t lo,
                std::int64_t hi, std::int64_t& out) {
  if (auto st = args.get_int(name, out); !st) return st;
  if (out < lo || out > hi) {
    return Status::error("--" + std::string(name) + " = " + std::to_string(out) + " is outside [" +
                         std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return {};
}

/// Reads the NSGA-II inputs; values not given keep what `s` holds.
Status read_settings(const stride::core::CliArgs& args, std::size_t real_genes, Settings& s) {
  opt::Nsga2Settings& n = s.config.settings;
  std::int64_t v = 0;
  if (args.has("seed")) {
    if (auto st = read_int(args, "seed", 0, INT64_MAX, v); !st) return st;
    n.seed = static_cast<std::uint64_t>(v);
  }
  if (args.has("pop")) {
    if (auto st = read_int(args, "pop", 0, 1000000, v); !st) return st;
    n.pop_size = static_cast<int>(v);
  }
  if (args.has("generations")) {
    if (auto st = read_int(args, "generations", 0, 1000000, v); !st) return st;
    n.generations = static_cast<int>(v);
  }
  const std::pair<const char*, double*> reals[] = {{"pc", &n.real_cross_prob},
                                                   {"etac", &n.eta_c},
                                                   {"pm", &n.real_mut_prob},
                                                   {"etam", &n.eta_m},
                                                   {"pbc", &n.bin_cross_prob},
                                                   {"pbm", &n.bin_mut_prob},
                                                   {"seed-fraction", &n.seed_mutation_fraction}};
  for (const auto& [name, target] : reals) {
    if (args.has(name)) {
      if (auto st = args.get_double(name, *target); !st) return st;
    }
  }
  if (!args.has("pm") && real_genes > 0) n.real_mut_prob = 1.0 / static_cast<double>(real_genes);
  if (auto st = opt::validate(n); !st) return st;
  return {};
}

void declare_options(stride::core::CliArgs& args) {
  args.option("problem", "test problem: " + problem_list())
      .option("config", "robot task config (optimiser/configs/walk.json, kick.json, ...)")
      .option("trials",
              "robust evaluation: K seeded randomised worlds per genome (overrides the config)")
      .option("aggregate", "how trials combine: mean or worst (overrides the config)")
      .option("engine",
              "robot tasks: physics engines of every trial, simbody|mujoco or a list "
              "(simbody,mujoco; repeatable; overrides the config's)")
      .option("out", "run directory to write (or resume)")
      .option("resume",
              "continue the run in --out from its checkpoint (with a larger --generations: extend "
              "a run, as if started with that total)",
              false)
      .option("seed", "random seed", true, "1")
      .option("pop", "population size (multiple of 4)", true, "100")
      .option("generations", "generations, the initial population included", true, "250")
      .option("pc", "realCrossProb: SBX probability per pair", true, "0.9")
      .option("etac", "etaC: SBX distribution index", true, "20")
      .option("pm", "realMutProb: mutation probability per real gene (default 1/n)")
      .option("etam", "etaM: polynomial mutation distribution index", true, "20")
      .option("pbc", "binCrossProb: single-point crossover probability per pair", true, "0.9")
      .option("pbm", "binMutProb: bit-flip probability per bit", true, "0.05")
      .option("start", "comma-separated real genes seeding the initial population")
      .option("seed-fraction", "fraction of genes mutated around --start", true, "0.2")
      .option("jobs", "evaluation threads (default: all cores)")
      .option("slow-eval-ms", "sleep this long in every evaluation (to test interruption)", true,
              "0")
      .option("mpi", "evaluate on MPI ranks (under mpirun: rank 0 optimises, the others evaluate)",
              false)
      .option("no-validate", "robot runs: skip `stride validate` at the end", false)
      .option("json", "print a JSON summary on stdout", false)
      .option("help", "show this help", false);
}

void print_help(const stride::core::CliArgs& args) {
  std::printf(
      "usage: stride optimise --problem NAME --out DIR [options]\n"
      "       stride optimise --config FILE --out DIR [--jobs N] [--trials K] [--aggregate "
      "mean|worst]\n"
      "       stride optimise --out DIR --resume [--generations N]   (N above the run's: extend "
      "it)\n"
      "Runs NSGA-II and writes run.json, evaluations.jsonl, generations.jsonl, checkpoint.json\n"
      "and pareto.csv to DIR; prints one progress line per generation on stderr.\n"
      "A robot run ends with `stride validate DIR` (validation.json; the config's\n"
      "validate.seeds seeds per world) unless --no-validate.\n\n%s",
      args.help().c_str());
}

/// --resume: the problem and settings recorded in DIR/run.json; a larger --generations extends
/// the run, any other NSGA-II option must be the run's. Errors are bad input.
Status resumed_problem(const stride::core::CliArgs& args, const std::filesystem::path& dir,
                       Settings& s, std::unique_ptr<opt::Problem>& problem) {
  if (!std::filesystem::exists(dir / "run.json"))
    return Status::error("--resume: " + (dir / "run.json").string() + " does not exist");
  if (auto st = opt::read_run_config(dir, s.config); !st) return st;
  if (args.has("problem") && args.get("problem") != s.config.problem)
    return Status::error("--problem " + args.get("problem") + " differs from the run's " +
                         s.config.problem);
  opt::TaskConfig task;
  const bool robot = opt::find_task_type(s.config.problem) != nullptr;
  if (robot) {
    if (auto st = opt::parse_task_record(s.config.task, task); !st)
      return Status::error("run.json task: " + st.message());
  } else if (auto st = make_problem(s.config.problem, problem); !st) {
    return st;
  }
  const opt::RunConfig recorded = s.config;
  if (auto st = read_settings(args, 0, s); !st) return st;
  // --generations above the run's extends it; every other option must be the run's.
  if (s.config.settings.generations < recorded.settings.generations)
    return Status::error("--generations: " + std::to_string(s.config.settings.generations) +
                         " is below the run's " + std::to_string(recorded.settings.generations) +
                         " (--resume can only extend a run)");
  opt::Nsga2Settings same = s.config.settings;
  same.generations = recorded.settings.generations;
  if (!(same == recorded.settings))
    return Status::error("--resume: the NSGA-II options given differ from the run's run.json");
  if (robot) {  // the task records its settings too: an extension changes both
    task.settings.generations = s.config.settings.generations;
    if (s.config.task.contains("generations"))
      s.config.task["generations"] = s.config.settings.generations;
    problem = std::make_unique<opt::RobotTask>(task);
  }
  return {};
}

/// --config FILE: a robot task, with --trials, --aggregate, --engine and the NSGA-II options
/// over the config's. Errors are bad input.
Status config_problem(const stride::core::CliArgs& args, Settings& s,
                      std::unique_ptr<opt::Problem>& problem) {
  if (args.has("problem")) return Status::error("--problem and --config exclude each other");
  opt::TaskConfig task;
  if (auto st = opt::load_task_config(args.get("config"), task); !st) return st;
  if (args.has("trials")) {
    std::int64_t trials = 1;
    if (auto st = read_int(args, "trials", 1, 1000, trials); !st) return st;
    task.trials = static_cast<int>(trials);
  }
  if (args.has("aggregate")) {
    const std::string a = args.get("aggregate");
    if (a != "mean" && a != "worst")
      return Status::error("--aggregate: must be mean or worst, got '" + a + "'");
    task.aggregate = a == "mean" ? opt::Aggregate::kMean : opt::Aggregate::kWorst;
  }
  if (args.has("engine")) {
    std::vector<stride::sim::EngineKind> engines;
    if (auto st = stride::sim::read_engine_list(args, "engine", engines); !st) return st;
    task.engines = engines;
    opt::apply_task_trial_step(task);  // a default step is the one these engines allow
  }
  s.config.settings = task.settings;
  if (auto st = read_settings(args, 0, s); !st) return st;
  task.settings = s.config.settings;
  auto robot_task = std::make_unique<opt::RobotTask>(task);
  if (auto st = robot_task->check(); !st) return st;
  s.config.problem = task.task;
  s.config.start = robot_task->start_genome();
  if (auto st = robot_task->extra_start_genomes(s.config.extra_starts); !st) return st;
  s.config.task = opt::to_json(task);
  problem = std::move(robot_task);
  return {};
}

/// --problem NAME: a test problem, with --start seeding it. Errors are bad input.
Status test_problem(const stride::core::CliArgs& args, Settings& s,
                    std::unique_ptr<opt::Problem>& problem) {
  if (!args.has("problem"))
    return Status::error("--problem NAME or --config FILE is required (" + problem_list() + ")");
  if (auto st = make_problem(args.get("problem"), problem); !st) return st;
  s.config.problem = problem->name();
  if (auto st = read_settings(args, problem->shape().reals.size(), s); !st) return st;
  if (args.has("start")) {
    opt::Genome start;
    if (auto st = parse_start(args.get("start"), start); !st) return st;
    if (auto st = opt::validate_genome(problem->shape(), start); !st)
      return Status::error("--start: " + st.message());
    s.config.start = start;
  }
  return {};
}

/// The problem and settings of this run: a resumed run, a robot task or a test problem, then
/// --jobs and --slow-eval-ms. `worker`: an MPI rank that only evaluates (writes nothing).
Status build_run(const stride::core::CliArgs& args, const std::filesystem::path& dir, bool worker,
                 Settings& s, std::unique_ptr<opt::Problem>& problem) {
  const bool resume = args.has("resume");
  Status built = resume               ? resumed_problem(args, dir, s, problem)
                 : args.has("config") ? config_problem(args, s, problem)
                                      : test_problem(args, s, problem);
  if (!built) return built;
  if (!resume && !worker && std::filesystem::exists(dir / "run.json"))
    return Status::error("--out " + dir.string() + " already holds a run (use --resume)");
  s.jobs = std::max<std::int64_t>(1, std::thread::hardware_concurrency());
  if (args.has("jobs")) {
    if (auto st = read_int(args, "jobs", 1, 1024, s.jobs); !st) return st;
  }
  return read_int(args, "slow-eval-ms", 0, 60000, s.slow_ms);
}

std::unique_ptr<opt::Evaluator> make_evaluator(const opt::MpiSession* mpi, std::int64_t jobs) {
  if (mpi) return std::make_unique<opt::MpiEvaluator>(mpi->size());
  if (jobs > 1) return std::make_unique<opt::ThreadPoolEvaluator>(static_cast<int>(jobs));
  return std::make_unique<opt::SerialEvaluator>();
}

/// Runs NSGA-II with the progress bar, SIGINT and SIGTERM stopping it after the generation in
/// flight (on_interrupt); the previous signal handlers are restored afterwards.
Status run_with_interrupts(const opt::Problem& problem, const Settings& s,
                           opt::Evaluator& evaluator, const std::filesystem::path& dir, bool resume,
                           opt::RunSummary& summary) {
  opt::RunOptions options;
  options.dir = dir;
  options.resume = resume;
  opt::ProgressPrinter progress(isatty(STDERR_FILENO) != 0);
  options.on_generation = [&progress](const opt::GenerationRecord& r) { progress.print(r); };
  options.on_rescore = [&progress](std::size_t members) {
    progress.finish();
    std::fprintf(stderr, "scoring the final front again on fresh worlds (%zu members)\n", members);
  };
  options.stop = &g_stop;
  g_stop.store(false);
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  struct sigaction previous_int {
  }, previous_term{};
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGTERM, &action, &previous_term);
  const Status run_status = opt::run_optimisation(problem, s.config, evaluator, options, summary);
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
  progress.finish();
  return run_status;
}

/// A robot run's files after the run: front/ parameter files and the SVG plots.
Status write_robot_outputs(const std::filesystem::path& dir, const opt::RobotTask& task) {
  if (auto st = opt::write_front_files(dir, task); !st) return st;
  if (auto st = opt::write_plots(dir); !st) return st;
  std::fprintf(stderr, "plots: %s, %s; front parameter files: %s\n",
               (dir / "pareto_by_generation.svg").c_str(), (dir / "hypervolume.svg").c_str(),
               (dir / "front").c_str());
  return {};
}

/// `stride validate DIR` at the end of a robot run: validation.json, and its path in
/// `validation`; skipped (with a line saying why) if the run cannot be loaded for it.
Status validate_run(const std::filesystem::path& dir, std::int64_t jobs,
                    nlohmann::json& validation) {
  opt::ValidationSubject subject;
  if (auto st = opt::load_validation_subject(dir, subject); !st) {
    errors.warning("validation skipped: " + st.message());
    return {};
  }
  opt::ValidationOptions v;
  v.seeds = subject.config.validate_seeds;
  v.jobs = static_cast<int>(jobs);
  v.progress = opt::validation_progress_printer(isatty(STDERR_FILENO) != 0);
  nlohmann::json result;
  Status done = opt::run_validation(subject, v, result);
  if (done) done = opt::write_validation_file(dir, result);
  if (!done) return Status::error("validation: " + done.message());
  std::fprintf(stderr, "%svalidation: %s\n", opt::validation_text(result).c_str(),
               (dir / "validation.json").c_str());
  validation = (dir / "validation.json").string();
  return {};
}

/// The --json summary: the run's last generation, its front and how it ended.
nlohmann::json summary_json(const Settings& s, const std::filesystem::path& dir,
                            const opt::RunSummary& summary, const nlohmann::json& validation) {
  auto number = [](const std::optional<double>& v) -> nlohmann::json {
    if (!v || !std::isfinite(*v)) return nullptr;
    return *v;
  };
  const opt::GenerationRecord& r = summary.last;
  return {{"problem", s.config.problem},
          {"out", dir.string()},
          {"seed", s.config.settings.seed},
          {"generations", r.generation},
          {"evaluations", r.evaluations},
          {"failures", r.failures},
          {"cache_hits", r.cache_hits},
          {"pareto_size", summary.pareto_size},
          {"hypervolume", number(r.hypervolume)},
          {"hypervolume_ratio", number(r.hypervolume_ratio)},
          {"igd", number(r.igd)},
          {"resumed", summary.resumed},
          {"resumed_at_generation", summary.resumed_at_generation},
          {"stopped", summary.stopped},
          {"validation", validation}};
}

}  // namespace

int run_optimise(int argc, char** argv) {
  stride::core::CliArgs args;
  declare_options(args);
  if (auto st = args.parse(argc, argv); !st) return errors.bad_input(st.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  if (!args.positional().empty())
    return errors.bad_input("unexpected argument '" + args.positional()[0] + "'");
  if (!args.has("out")) return errors.bad_input("--out DIR is required");
  const std::filesystem::path dir = args.get("out");
  std::unique_ptr<opt::MpiSession> mpi;
  if (args.has("mpi")) {
    if (!opt::mpi_available()) return errors.bad_input("--mpi: this build of stride has no MPI");
    mpi = std::make_unique<opt::MpiSession>(nullptr, nullptr);
  }
  const bool worker = mpi && mpi->rank() != 0;  // evaluates only; rank 0 owns the run directory

  Settings s;
  std::unique_ptr<opt::Problem> problem;
  if (auto st = build_run(args, dir, worker, s, problem); !st)
    return errors.bad_input(st.message());
  if (worker) {
    if (auto st = opt::run_mpi_worker(*problem); !st)
      return errors.failure("rank " + std::to_string(mpi->rank()) + ": " + st.message());
    return 0;
  }
  const auto* robot_task = dynamic_cast<const opt::RobotTask*>(problem.get());
  if (s.slow_ms > 0) {
    problem =
        std::make_unique<SlowProblem>(std::move(problem), std::chrono::milliseconds(s.slow_ms));
  }
  const std::unique_ptr<opt::Evaluator> evaluator = make_evaluator(mpi.get(), s.jobs);
  opt::RunSummary summary;
  if (auto st = run_with_interrupts(*problem, s, *evaluator, dir, args.has("resume"), summary); !st)
    return errors.failure(st.message());

  nlohmann::json validation = nullptr;
  if (robot_task != nullptr) {
    if (auto st = write_robot_outputs(dir, *robot_task); !st) return errors.failure(st.message());
    if (!summary.stopped && !args.has("no-validate")) {
      if (auto st = validate_run(dir, s.jobs, validation); !st) return errors.failure(st.message());
    }
  }
  if (summary.stopped) {
    std::fprintf(stderr,
                 "stride optimise: stopped after generation %d (checkpoint written); continue with "
                 "--out %s --resume\n",
                 summary.last.generation, dir.c_str());
  }
  if (args.has("json"))
    std::printf("%s\n", summary_json(s, dir, summary, validation).dump().c_str());
  return summary.stopped ? 130 : 0;
}

STRIDE_COMMAND(optimise, "run NSGA-II on a test problem (or a task) into a run directory",
               run_optimise);
