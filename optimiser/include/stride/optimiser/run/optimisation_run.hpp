// An optimisation run in a run directory, with checkpoint/resume.
//
// Files in the run directory (docs/formats.md, "Run directory"):
//   run.json           problem, settings, start genome, task config, Stride version
//   evaluations.jsonl  one line per evaluation actually made (cache hits are not re-logged), in
//                      batch order whatever order the evaluator finishes in
//   generations.jsonl  one line per generation: counters, front size, hypervolume, IGD, wall_s
//   checkpoint.json    the optimiser state after the last completed generation, plus how many
//                      lines of the two logs belong to it; replaced atomically every generation
//   pareto.csv         the current population's non-dominated members: objectives then genes
//   front-rescored.json  a resampling run (Nsga2Settings::resample), once finished: every
//                      pareto.csv row scored again on fresh worlds (kRescoreDraw), from which
//                      its picks are named (report::run_picks)
// Resume reads checkpoint.json, cuts both logs back to the recorded line counts (dropping the
// work of the interrupted generation), refills the evaluation cache from evaluations.jsonl and
// continues; the files then end up byte for byte as in an uninterrupted run (wall_s aside).
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/optimiser/nsga2/evaluator.hpp"
#include "stride/optimiser/nsga2/nsga2.hpp"
#include "stride/optimiser/nsga2/problem.hpp"

namespace stride::opt {

struct RunConfig {
  std::string problem;  ///< problem or task name
  Nsga2Settings settings;
  std::optional<Genome> start;  ///< seeds the initial population when set
  /// Further start genomes beside `start` (needs `start`): the initial population holds each
  /// unmutated and mutated copies of all in turn (Nsga2::create). run.json's "extra_starts".
  std::vector<Genome> extra_starts;
  nlohmann::json task = nlohmann::json::object();  ///< task configuration, recorded as is
};

struct GenerationRecord {
  int generation = 0;  ///< completed generations (1 = the initial population)
  int generations = 0;
  std::uint64_t evaluations = 0;
  std::uint64_t failures = 0;
  std::uint64_t cache_hits = 0;
  int feasible = 0;                         ///< feasible members of the population
  int front_size = 0;                       ///< members of the first front
  std::optional<double> hypervolume;        ///< normalised, reference point 1.1 per objective
  std::optional<double> hypervolume_ratio;  ///< hypervolume / the true front's
  std::optional<double> igd;                ///< normalised
  double wall_s = 0.0;                      ///< time spent on this generation
  std::vector<double> best_objectives;      ///< per objective, best feasible value (empty: none)
};

struct RunOptions {
  std::filesystem::path dir;
  bool resume = false;
  std::function<void(const GenerationRecord&)> on_generation;
  /// When set and true after a generation's checkpoint, the run stops there (Ctrl-C).
  const std::atomic<bool>* stop = nullptr;
  /// Called before a resampling run scores its final front again (the member count).
  std::function<void(std::size_t members)> on_rescore;
};

struct RunSummary {
  bool resumed = false;
  int resumed_at_generation = 0;
  GenerationRecord last;
  std::size_t pareto_size = 0;
  bool stopped = false;  ///< ended early by RunOptions::stop (resume with --resume)
};

/// The run.json contents for a problem and configuration.
nlohmann::json run_description(const Problem& problem, const RunConfig& config);
/// Reads run.json of an existing run (for --resume).
Status read_run_config(const std::filesystem::path& dir, RunConfig& config);
/// Indicators of a population (feasible first-front members) against the problem's reference.
GenerationRecord measure(const Problem& problem, const std::vector<Individual>& population,
                         const std::optional<FrontReference>& reference);
/// Runs (or resumes) the optimisation to its last generation.
Status run_optimisation(const Problem& problem, const RunConfig& config, Evaluator& evaluator,
                        const RunOptions& options, RunSummary& summary);

}  // namespace stride::opt
