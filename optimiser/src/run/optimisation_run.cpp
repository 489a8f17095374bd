// run_optimisation(): the ask/evaluate/tell loop writing the run directory (see the header).
#include "stride/optimiser/run/optimisation_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <sstream>

#include "stride/core/atomic_file.hpp"
#include "stride/core/json_file.hpp"
#include "stride/optimiser/nsga2/indicators.hpp"
#include "stride/optimiser/run/log_files.hpp"

namespace stride::opt {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr const char* kRunFormat = "stride-optimiser-run";
constexpr const char* kStrideVersion = "0.1.0";

json settings_json(const Nsga2Settings& s) {
  json j{{"seed", s.seed},
         {"popSize", s.pop_size},
         {"generations", s.generations},
         {"realCrossProb", s.real_cross_prob},
         {"realMutProb", s.real_mut_prob},
         {"etaC", s.eta_c},
         {"etaM", s.eta_m},
         {"binCrossProb", s.bin_cross_prob},
         {"binMutProb", s.bin_mut_prob},
         {"seedMutationFraction", s.seed_mutation_fraction}};
  if (s.resample) j["resample"] = true;  // only when on: older run.json files stay equal
  return j;
}

json shape_json(const ProblemShape& shape) {
  json reals = json::array();
  for (const RealLimits& l : shape.reals) reals.push_back({l.min, l.max});
  json bins = json::array();
  for (const BinaryGene& b : shape.binaries)
    bins.push_back({{"bits", b.bits}, {"limits", {b.min, b.max}}});
  return json{{"objectives", shape.objectives},
              {"constraints", shape.constraints},
              {"realLimits", reals},
              {"binaries", bins}};
}

json evaluation_line(const Individual& ind, int generation) {
  return json{{"id", ind.id},
              {"generation", generation},
              {"reals", ind.genome.reals},
              {"bits", bits_to_text(ind.genome.bits)},
              {"objectives", ind.result.objectives},
              {"constraints", ind.result.constraints},
              {"violation", ind.result.violation},
              {"failed", ind.result.failed},
              {"reason", ind.result.reason}};
}

Status parse_evaluation_line(const std::string& line, std::pair<Genome, Result>& out) {
  try {
    const json j = json::parse(line);
    out.first.reals = j.at("reals").get<std::vector<double>>();
    if (!bits_from_text(j.at("bits").get<std::string>(), out.first.bits)) {
      return Status::error("evaluations.jsonl: bits are not 0/1 text");
    }
    out.second.objectives = j.at("objectives").get<std::vector<double>>();
    out.second.constraints = j.at("constraints").get<std::vector<double>>();
    out.second.violation = j.at("violation").get<double>();
    out.second.failed = j.at("failed").get<bool>();
    out.second.reason = j.at("reason").get<std::string>();
  } catch (const json::exception& e) {
    return Status::error(std::string("evaluations.jsonl: malformed line: ") + e.what());
  }
  return {};
}

json optional_number(const std::optional<double>& v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  return *v;
}

json generation_line(const GenerationRecord& r) {
  return json{{"generation", r.generation},
              {"evaluations", r.evaluations},
              {"failures", r.failures},
              {"cache_hits", r.cache_hits},
              {"feasible", r.feasible},
              {"front_size", r.front_size},
              {"hypervolume", optional_number(r.hypervolume)},
              {"hypervolume_ratio", optional_number(r.hypervolume_ratio)},
              {"igd", optional_number(r.igd)},
              {"wall_s", r.wall_s}};
}

std::string number_text(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

/// The distinct genomes of the first front, sorted by objectives: pareto.csv's rows.
std::vector<const Individual*> front_rows(const std::vector<Individual>& population) {
  std::vector<const Individual*> members;
  std::set<std::string> seen;
  for (const Individual& ind : population) {
    if (ind.rank == 0 && seen.insert(genome_key(ind.genome)).second) members.push_back(&ind);
  }
  std::sort(members.begin(), members.end(), [](const Individual* a, const Individual* b) {
    if (a->result.objectives != b->result.objectives) {
      return a->result.objectives < b->result.objectives;
    }
    return a->id < b->id;
  });
  return members;
}

/// pareto.csv: the distinct genomes of the first front, sorted by objectives.
std::string pareto_csv(const ProblemShape& shape, const std::vector<Individual>& population,
                       std::size_t& rows) {
  const std::vector<const Individual*> members = front_rows(population);
  std::string text;
  for (int m = 0; m < shape.objectives; ++m) text += (m ? ",f" : "f") + std::to_string(m + 1);
  for (std::size_t k = 0; k < shape.reals.size(); ++k) text += ",x" + std::to_string(k + 1);
  for (std::size_t k = 0; k < shape.binaries.size(); ++k) text += ",b" + std::to_string(k + 1);
  text += "\n";
  for (const Individual* ind : members) {
    std::string row;
    for (const double f : ind->result.objectives) row += (row.empty() ? "" : ",") + number_text(f);
    for (const double x : ind->genome.reals) row += "," + number_text(x);
    for (const double b : decode_binaries(shape, ind->genome)) row += "," + number_text(b);
    text += row + "\n";
  }
  rows = members.size();
  return text;
}

/// front-rescored.json: every pareto.csv row scored again on kRescoreDraw, in row order.
Status rescore_front(const Problem& problem, Evaluator& evaluator,
                     const std::vector<Individual>& population, const fs::path& path) {
  const std::vector<const Individual*> rows = front_rows(population);
  std::vector<Candidate> batch;
  for (const Individual* ind : rows) batch.push_back(Candidate{ind->id, ind->genome, kRescoreDraw});
  std::vector<std::optional<Result>> results(batch.size());
  evaluator.evaluate(problem, batch, [&](std::size_t index, EvaluationOutcome outcome) {
    if (index < results.size()) results[index] = sanitise(problem.shape(), std::move(outcome));
  });
  json members = json::array();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!results[i])
      return Status::error("rescoring: pareto.csv row " + std::to_string(i) + " got no result");
    const Result& r = *results[i];
    members.push_back({{"row", i},
                       {"id", rows[i]->id},
                       {"objectives", r.objectives},
                       {"constraints", r.constraints},
                       {"violation", r.violation},
                       {"failed", r.failed},
                       {"reason", r.reason},
                       {"run_objectives", rows[i]->result.objectives}});
  }
  const json doc = {{"draw", kRescoreDraw}, {"members", members}};
  return core::write_file_atomically(path, doc.dump(1) + "\n");
}

}  // namespace

json run_description(const Problem& problem, const RunConfig& config) {
  const auto genome_json = [](const Genome& g) {
    return json{{"reals", g.reals}, {"bits", bits_to_text(g.bits)}};
  };
  json j{{"format", kRunFormat},
         {"format_version", 1},
         {"stride_version", kStrideVersion},
         {"problem", config.problem.empty() ? problem.name() : config.problem},
         {"settings", settings_json(config.settings)},
         {"shape", shape_json(problem.shape())},
         {"start", config.start ? genome_json(*config.start) : json(nullptr)},
         {"task", config.task}};
  if (!config.extra_starts.empty()) {  // only when given: older run.json files stay equal
    j["extra_starts"] = json::array();
    for (const Genome& g : config.extra_starts) j["extra_starts"].push_back(genome_json(g));
  }
  return j;
}

namespace {

/// The start genomes of a run: `start`, then `extra_starts`.
std::vector<Genome> start_genomes(const RunConfig& config) {
  std::vector<Genome> starts;
  if (config.start) starts.push_back(*config.start);
  starts.insert(starts.end(), config.extra_starts.begin(), config.extra_starts.end());
  return starts;
}

Status parse_genome_json(const json& j, const char* field, Genome& g) {
  g.reals = j.at("reals").get<std::vector<double>>();
  if (!bits_from_text(j.at("bits").get<std::string>(), g.bits))
    return Status::error(std::string("run.json: ") + field + ".bits are not 0/1 text");
  return {};
}

}  // namespace

Status read_run_config(const fs::path& dir, RunConfig& config) {
  json j;
  if (auto st = core::read_json_file(dir / "run.json", j); !st) return st;
  try {
    if (j.at("format").get<std::string>() != kRunFormat) {
      return Status::error((dir / "run.json").string() + " is not a Stride run description");
    }
    config.problem = j.at("problem").get<std::string>();
    const json& s = j.at("settings");
    config.settings.seed = s.at("seed").get<std::uint64_t>();
    config.settings.pop_size = s.at("popSize").get<int>();
    config.settings.generations = s.at("generations").get<int>();
    config.settings.real_cross_prob = s.at("realCrossProb").get<double>();
    config.settings.real_mut_prob = s.at("realMutProb").get<double>();
    config.settings.eta_c = s.at("etaC").get<double>();
    config.settings.eta_m = s.at("etaM").get<double>();
    config.settings.bin_cross_prob = s.at("binCrossProb").get<double>();
    config.settings.bin_mut_prob = s.at("binMutProb").get<double>();
    config.settings.seed_mutation_fraction = s.at("seedMutationFraction").get<double>();
    config.settings.resample = s.value("resample", false);
    config.start.reset();
    if (!j.at("start").is_null()) {
      Genome g;
      if (auto st = parse_genome_json(j["start"], "start", g); !st) return st;
      config.start = g;
    }
    config.extra_starts.clear();
    for (const json& e : j.value("extra_starts", json::array())) {
      Genome g;
      if (auto st = parse_genome_json(e, "extra_starts", g); !st) return st;
      config.extra_starts.push_back(std::move(g));
    }
    config.task = j.at("task");
  } catch (const json::exception& e) {
    return Status::error((dir / "run.json").string() + ": malformed (" + e.what() + ")");
  }
  return {};
}

GenerationRecord measure(const Problem& problem, const std::vector<Individual>& population,
                         const std::optional<FrontReference>& reference) {
  GenerationRecord r;
  Points front;
  for (const Individual& ind : population) {
    if (!ind.result.feasible()) continue;
    ++r.feasible;
    if (ind.rank == 0) front.push_back(ind.result.objectives);
  }
  r.front_size = static_cast<int>(front.size());
  if (reference && !reference->ideal.empty()) {
    const Points normalised = normalise(front, reference->ideal, reference->nadir);
    r.hypervolume = hypervolume(
        normalised, std::vector<double>(static_cast<std::size_t>(problem.shape().objectives), 1.1));
    if (reference->true_hypervolume && *reference->true_hypervolume > 0) {
      r.hypervolume_ratio = *r.hypervolume / *reference->true_hypervolume;
    }
    if (!reference->front.empty()) {
      r.igd = igd(normalised, normalise(reference->front, reference->ideal, reference->nadir));
    }
  }
  return r;
}

namespace {

/// The files of a run directory that run_optimisation writes.
struct RunFiles {
  explicit RunFiles(const fs::path& dir)
      : run(dir / "run.json"),
        checkpoint(dir / "checkpoint.json"),
        evaluations(dir / "evaluations.jsonl"),
        generations(dir / "generations.jsonl"),
        pareto(dir / "pareto.csv"),
        rescored(dir / "front-rescored.json") {}
  fs::path run, checkpoint, evaluations, generations, pareto, rescored;
};

/// --resume: the engine as of the last checkpoint (or a fresh one if the run never wrote one),
/// the logs cut back to it; a larger total of generations extends the run.
Status resume_engine(const Problem& problem, const RunConfig& config, const json& description,
                     const RunFiles& files, std::unique_ptr<Nsga2>& engine) {
  json existing;
  if (auto st = core::read_json_file(files.run, existing); !st) return st;
  // A larger total of generations extends the run (written to run.json once restored).
  const int recorded_generations =
      existing.contains("settings") ? existing["settings"].value("generations", 0) : 0;
  const bool extends = config.settings.generations > recorded_generations;
  if (extends) {
    existing["settings"]["generations"] = config.settings.generations;
    if (existing.contains("task") && existing["task"].is_object() &&
        existing["task"].contains("generations"))
      existing["task"]["generations"] = config.settings.generations;  // a robot task's record
  }
  if (existing != description) {
    return Status::error(files.run.string() +
                         " describes another run (problem, settings or "
                         "task differ)");
  }
  std::size_t evaluation_lines = 0;
  std::size_t generation_lines = 0;
  json cp;
  const bool have_checkpoint = fs::exists(files.checkpoint);
  if (have_checkpoint) {
    if (auto st = core::read_json_file(files.checkpoint, cp); !st) return st;
    try {
      evaluation_lines = cp.at("run").at("evaluation_lines").get<std::size_t>();
      generation_lines = cp.at("run").at("generation_lines").get<std::size_t>();
    } catch (const json::exception& e) {
      return Status::error(files.checkpoint.string() + ": malformed (" + e.what() + ")");
    }
  }
  std::vector<std::string> lines;
  if (auto st = keep_first_lines(files.generations, generation_lines, lines); !st) return st;
  if (auto st = keep_first_lines(files.evaluations, evaluation_lines, lines); !st) return st;
  std::vector<std::pair<Genome, Result>> known(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (auto st = parse_evaluation_line(lines[i], known[i]); !st) return st;
  }
  if (have_checkpoint) {
    if (auto st = Nsga2::restore(cp.at("engine"), problem.shape(), known, engine); !st) {
      return Status::error(files.checkpoint.string() + ": " + st.message());
    }
  } else if (auto st =
                 Nsga2::create(config.settings, problem.shape(), start_genomes(config), engine);
             !st) {
    return st;
  }
  if (extends) {
    if (auto st = engine->extend(config.settings.generations); !st) return st;
    if (auto st = core::write_file_atomically(files.run, description.dump(2) + "\n"); !st)
      return st;
  }
  return {};
}

/// A new run: the engine from the config's settings and start genomes, and run.json.
Status start_engine(const Problem& problem, const RunConfig& config, const json& description,
                    const fs::path& dir, const RunFiles& files, std::unique_ptr<Nsga2>& engine) {
  if (fs::exists(files.run) || fs::exists(files.checkpoint) || fs::exists(files.evaluations)) {
    return Status::error(dir.string() + " already holds a run (use --resume or another --out)");
  }
  if (auto st = Nsga2::create(config.settings, problem.shape(), start_genomes(config), engine);
      !st) {
    return st;
  }
  return core::write_file_atomically(files.run, description.dump(2) + "\n");
}

/// Evaluates one batch and tells the engine every result; results are logged in batch order,
/// out-of-order ones waiting until their turn.
Status evaluate_batch(const Problem& problem, Evaluator& evaluator, Nsga2& engine,
                      const std::vector<Candidate>& batch, int generation, LineLog& evaluations) {
  std::vector<bool> told(batch.size(), false);
  std::size_t next_to_log = 0;
  Status failure;
  evaluator.evaluate(problem, batch, [&](std::size_t index, EvaluationOutcome outcome) {
    if (!failure.is_ok() || index >= batch.size() || told[index]) return;
    if (auto st = engine.tell(batch[index].id, std::move(outcome)); !st) {
      failure = st;
      return;
    }
    told[index] = true;
    while (next_to_log < batch.size() && told[next_to_log]) {
      const Individual* ind = engine.batch_member(batch[next_to_log].id);
      if (auto st = evaluations.append(evaluation_line(*ind, generation).dump()); !st) {
        failure = st;
        return;
      }
      ++next_to_log;
    }
  });
  return failure;
}

/// The engine's state as a generation record (without its wall time and best objectives).
GenerationRecord current_record(const Problem& problem, const Nsga2& engine,
                                const std::optional<FrontReference>& reference,
                                int generations_planned) {
  GenerationRecord record = measure(problem, engine.population(), reference);
  record.generation = engine.completed_generations();
  record.generations = generations_planned;
  record.evaluations = engine.counters().evaluations;
  record.failures = engine.counters().failures;
  record.cache_hits = engine.counters().cache_hits;
  return record;
}

/// The best value of each objective over the population's feasible, unfailed members (empty if
/// there are none).
std::vector<double> best_objectives(const std::vector<Individual>& population) {
  std::vector<double> best;
  for (const Individual& ind : population) {
    if (ind.result.failed || ind.result.violation > 0.0) continue;
    if (best.empty()) best = ind.result.objectives;
    for (std::size_t m = 0; m < best.size(); ++m)
      best[m] = std::min(best[m], ind.result.objectives[m]);
  }
  return best;
}

}  // namespace

Status run_optimisation(const Problem& problem, const RunConfig& config, Evaluator& evaluator,
                        const RunOptions& options, RunSummary& summary) {
  const fs::path& dir = options.dir;
  const json description = run_description(problem, config);
  const RunFiles files(dir);

  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return Status::error(dir.string() + ": cannot create (" + ec.message() + ")");

  std::unique_ptr<Nsga2> engine;
  summary = RunSummary{};
  if (options.resume) {
    if (auto st = resume_engine(problem, config, description, files, engine); !st) return st;
    summary.resumed = true;
    summary.resumed_at_generation = engine->completed_generations();
  } else if (auto st = start_engine(problem, config, description, dir, files, engine); !st) {
    return st;
  }

  LineLog evaluations;
  LineLog generations;
  if (auto st = evaluations.open(files.evaluations); !st) return st;
  if (auto st = generations.open(files.generations); !st) return st;
  const std::optional<FrontReference> reference = problem.reference();

  auto write_checkpoint = [&]() -> Status {
    if (auto st = evaluations.sync(); !st) return st;
    if (auto st = generations.sync(); !st) return st;
    const json cp = {
        {"engine", engine->checkpoint()},
        {"run",
         {{"evaluation_lines", evaluations.lines()}, {"generation_lines", generations.lines()}}}};
    return core::write_file_atomically(files.checkpoint, cp.dump() + "\n");
  };
  if (!options.resume) {
    if (auto st = write_checkpoint(); !st) return st;
  }

  while (!engine->finished()) {
    const auto started = std::chrono::steady_clock::now();
    const std::vector<Candidate> batch = engine->ask();
    const int generation = engine->completed_generations() + 1;
    if (auto st = evaluate_batch(problem, evaluator, *engine, batch, generation, evaluations); !st)
      return st;
    if (auto st = engine->advance(); !st) return st;
    GenerationRecord record =
        current_record(problem, *engine, reference, config.settings.generations);
    record.wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (auto st = generations.append(generation_line(record).dump()); !st) return st;
    std::size_t rows = 0;
    const std::string csv = pareto_csv(problem.shape(), engine->population(), rows);
    if (auto st = core::write_file_atomically(files.pareto, csv); !st) return st;
    if (auto st = write_checkpoint(); !st) return st;
    summary.last = record;
    summary.pareto_size = rows;
    record.best_objectives = best_objectives(engine->population());
    summary.last = record;
    if (options.on_generation) options.on_generation(record);
    if (options.stop != nullptr && options.stop->load() && !engine->finished()) {
      summary.stopped = true;
      break;
    }
  }
  // A resampling run's final front, scored again on worlds no generation saw.
  if (config.settings.resample && engine->finished() &&
      (summary.last.generation != 0 || !fs::exists(files.rescored))) {
    if (options.on_rescore) options.on_rescore(front_rows(engine->population()).size());
    if (auto st = rescore_front(problem, evaluator, engine->population(), files.rescored); !st)
      return st;
  }
  if (summary.last.generation == 0) {  // resumed a finished run: report its final state
    summary.last = current_record(problem, *engine, reference, config.settings.generations);
    std::size_t rows = 0;
    pareto_csv(problem.shape(), engine->population(), rows);
    summary.pareto_size = rows;
  }
  return {};
}

}  // namespace stride::opt
