// Validation of a robot run: the subject (Ind_O and the picks), the worlds, and the episodes on
// the thread-pool evaluator (see validation.hpp). Summaries and text: validation_summary.cpp.
#include "stride/optimiser/run/validation.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>

#include "stride/core/atomic_file.hpp"
#include "stride/optimiser/nsga2/evaluator.hpp"
#include "stride/optimiser/report/run_data.hpp"
#include "stride/optimiser/run/optimisation_run.hpp"
#include "stride/optimiser/run/validation_summary.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::opt {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr sim::EngineKind kAllEngines[] = {sim::EngineKind::kSimbody, sim::EngineKind::kMujoco};

/// The episodes of a validation as a Problem for the evaluators: genome.reals[0] is the index
/// of the episode; each call writes only its own slot of `results`, so threads never share one.
class ValidationEpisodes final : public Problem {
 public:
  struct Episode {
    std::size_t individual, world, seed;
  };
  ValidationEpisodes(const RobotTask& task, const std::vector<ValidationIndividual>& individuals,
                     const std::vector<ValidationWorld>& worlds, std::vector<Episode> episodes,
                     std::vector<EpisodeOutcome>& results)
      : task_(task),
        individuals_(individuals),
        worlds_(worlds),
        episodes_(std::move(episodes)),
        results_(results) {}
  std::string name() const override { return "validation"; }
  const ProblemShape& shape() const override { return shape_; }
  EvaluationOutcome evaluate(const Genome& genome) const override {
    const auto index = static_cast<std::size_t>(genome.reals.at(0));
    const Episode& e = episodes_.at(index);
    const sim::WorldOptions options = validation_episode_world(task_, worlds_[e.world], e.seed);
    EpisodeOutcome& out = results_[index];
    if (Status s = task_.run_world(individuals_[e.individual].genome, options, out.score); !s) {
      out.setup_error = s.message();
      return EvaluationOutcome::failure(s.message());
    }
    return {};
  }

 private:
  const RobotTask& task_;
  const std::vector<ValidationIndividual>& individuals_;
  const std::vector<ValidationWorld>& worlds_;
  std::vector<Episode> episodes_;
  std::vector<EpisodeOutcome>& results_;
  ProblemShape shape_;
};

bool contains(const std::vector<sim::EngineKind>& list, sim::EngineKind kind) {
  return std::find(list.begin(), list.end(), kind) != list.end();
}

}  // namespace

Status load_validation_subject(const fs::path& dir, ValidationSubject& out,
                               const std::vector<std::size_t>& members) {
  if (!fs::exists(dir / "run.json"))
    return Status::error(dir.string() + " is not a run directory (no run.json)");
  RunConfig run;
  if (Status s = read_run_config(dir, run); !s) return s;
  if (find_task_type(run.problem) == nullptr)
    return Status::error(dir.string() + " is a '" + run.problem + "' run, not a robot run (" +
                         task_type_list() + ")");
  ValidationSubject subject;
  subject.dir = dir;
  if (Status s = parse_task_record(run.task, subject.config); !s)
    return Status::error("run.json task: " + s.message());
  report::RunData data;
  if (Status s = report::load_run_data(dir, data); !s) return s;
  const std::vector<report::RunPick> picks = report::run_picks(data);
  if (picks.empty())
    return Status::error(dir.string() + " has no picks to validate (pareto.csv has no front " +
                         "members)");
  ValidationIndividual ind_o;
  ind_o.name = "Ind_O";
  for (const auto& g : subject.config.genes) ind_o.genome.reals.push_back(g.start);
  if (const json* logged = report::find_ind_o(data))
    ind_o.run_objectives = report::objectives_of(*logged);
  subject.individuals.push_back(ind_o);
  for (const report::RunPick& p : picks) {
    ValidationIndividual ind;
    ind.name = p.label;
    ind.file = p.file;
    ind.genome.reals = p.genes;
    ind.run_objectives = p.objectives;
    if (ind.genome.reals.size() != subject.config.genes.size())
      return Status::error(p.file + ": has " + std::to_string(p.genes.size()) +
                           " genes, the task " + std::to_string(subject.config.genes.size()));
    subject.individuals.push_back(std::move(ind));
  }
  for (const std::size_t row : members) {
    if (row >= data.front.size())
      return Status::error("--member: " + std::to_string(row) +
                           " is not a front row (pareto.csv has " +
                           std::to_string(data.front.size()) + ", 0.." +
                           std::to_string(data.front.size() - 1) + ")");
    bool listed = false;
    for (const report::RunPick& p : picks) listed = listed || p.front_index == row;
    for (const ValidationIndividual& i : subject.individuals)
      listed = listed || i.file == report::front_file_name(row);
    if (listed) continue;
    ValidationIndividual ind;
    ind.file = report::front_file_name(row);
    ind.name = ind.file;
    ind.genome.reals = data.front[row].genes;
    ind.run_objectives = data.front[row].objectives;
    if (ind.genome.reals.size() != subject.config.genes.size())
      return Status::error(ind.file + ": has " + std::to_string(ind.genome.reals.size()) +
                           " genes, the task " + std::to_string(subject.config.genes.size()));
    subject.individuals.push_back(std::move(ind));
  }
  out = std::move(subject);
  return {};
}

Status validation_worlds(const RobotTask& task, const ValidationOptions& options,
                         std::vector<ValidationWorld>& out) {
  out.clear();
  if (options.seeds < 1 || options.seeds > 1000)
    return Status::error("--seeds: " + std::to_string(options.seeds) + " is outside [1, 1000]");
  const TaskConfig& config = task.config();
  sim::WorldSpec base = task.world_spec(0);
  base.noise = true;  // the run's IMU model, with its noise on
  // Half the run's step, in whole microseconds (the table's unit).
  const std::int64_t step_ns =
      options.physics_step_ns > 0 ? options.physics_step_ns : base.physics_step_us * 1000 / 2;
  if (step_ns % 1000 != 0)
    return Status::error("--physics-step-us: half the run's step (" +
                         std::to_string(base.physics_step_us) +
                         " us) is not a whole number of microseconds; give the step");
  if (Status s = sim::check_physics_step(step_ns, task.control_period_ns(), "--physics-step-us");
      !s)
    return s;
  std::vector<std::uint64_t> seeds;
  for (int i = 0; i < options.seeds; ++i)
    seeds.push_back(config.trial_seed + kValidationSeedOffset + static_cast<std::uint64_t>(i));
  base.seed = seeds.front();  // each world's spec is its first episode's (the record's seed)
  std::vector<sim::EngineKind> engines = options.engines;
  if (engines.empty())
    for (sim::EngineKind e : kAllEngines)
      if (!contains(config.engines, e)) engines.push_back(e);
  const TaskType* type = find_task_type(config.task);
  for (sim::EngineKind e : engines) {
    ValidationWorld w{std::string("engine ") + sim::to_string(e), base, seeds};
    w.world.engine = e;
    // At most the step the task allows on that engine (a Simbody run's 2.5 ms is 2 ms on MuJoCo,
    // TaskType::trial_physics_step_us): the other engine checks the walk, not its own step.
    if (type != nullptr)
      w.world.physics_step_us =
          std::min(w.world.physics_step_us, type->descriptor().trial_physics_step_us(e));
    out.push_back(std::move(w));
  }
  out.push_back({"fresh seeds", base, seeds});
  ValidationWorld wider{"wider randomisation", base, seeds};
  sim::Randomisation& r = wider.world.randomise;
  auto widen = [](double run, double floor) { return std::min(0.9, std::max(1.5 * run, floor)); };
  r.friction_range = widen(r.friction_range, 1.5 * TrialRandomisation{}.friction_range);
  r.mass_range = widen(r.mass_range, 1.5 * TrialRandomisation{}.mass_range);
  r.strength_range = widen(r.strength_range, 1.5 * TrialRandomisation{}.strength_range);
  r.contact_range = widen(r.contact_range, 0.0);    // the run's ground range, if it had one
  r.com_range = std::min(0.05, 1.5 * r.com_range);  // the run's robot variants, if it had them
  r.latency_probability = std::max(0.5, r.latency_probability);
  out.push_back(std::move(wider));
  // The robot as it may be (issue 54 point 2): worn or weak servos and a battery anywhere
  // between flat and full, beside the run's randomisation. A run whose trials draw the servos
  // already has this world in "fresh seeds": not run twice.
  const sim::Randomisation& run = base.randomise;
  const bool run_draws_servos = run.servo_friction_min != run.servo_friction_max ||
                                run.servo_torque_min != run.servo_torque_max ||
                                run.supply_max_v > 0.0;
  ValidationWorld servos{"servos off the model", base, seeds};
  sim::Randomisation& o = servos.world.randomise;
  o.servo_friction_min = kOffModelServos.servo_friction_min;
  o.servo_friction_max = kOffModelServos.servo_friction_max;
  o.servo_torque_min = kOffModelServos.servo_torque_min;
  o.servo_torque_max = kOffModelServos.servo_torque_max;
  o.supply_min_v = kOffModelServos.supply_min_v;
  o.supply_max_v = kOffModelServos.supply_max_v;
  o.latency_probability = std::max(0.5, o.latency_probability);
  if (!run_draws_servos) out.push_back(std::move(servos));
  ValidationWorld half{options.physics_step_ns > 0
                           ? "step " + std::to_string(step_ns / 1000) + " us"
                           : std::string("half step"),
                       base, seeds};
  half.world.physics_step_us = step_ns / 1000;
  out.push_back(std::move(half));
  // The grounds on either side of turf, with the run's friction (the one its ground had).
  const double friction = task.world_options(base).contact.friction;
  for (const char* ground : {"soft", "hard"}) {
    ValidationWorld w{std::string("ground ") + ground, base, seeds};
    w.world.contact = ground;
    w.world.friction = friction;
    w.world.randomise.contact_range = 0.0;
    out.push_back(std::move(w));
  }
  return {};
}

sim::WorldOptions validation_episode_world(const RobotTask& task, const ValidationWorld& world,
                                           std::size_t seed) {
  sim::WorldSpec spec = world.world;
  spec.seed = world.seeds.at(seed);
  return task.world_options(spec);
}

Status run_validation(const ValidationSubject& subject, const ValidationOptions& options,
                      json& out) {
  const RobotTask task(subject.config);
  std::vector<ValidationWorld> worlds;
  if (Status s = validation_worlds(task, options, worlds); !s) return s;
  std::vector<ValidationIndividual> individuals = subject.individuals;
  // Ind_O's own score: from the log, else evaluated again in the run's worlds.
  for (ValidationIndividual& ind : individuals) {
    if (ind.run_objectives.size() >= 2) continue;
    const EvaluationOutcome o = task.evaluate(ind.genome);
    if (o.failed) return Status::error(ind.name + " in the run's world: " + o.reason);
    ind.run_objectives = o.objectives;
  }
  std::vector<ValidationEpisodes::Episode> episodes;
  for (std::size_t i = 0; i < individuals.size(); ++i)
    for (std::size_t w = 0; w < worlds.size(); ++w)
      for (std::size_t s = 0; s < worlds[w].seeds.size(); ++s) episodes.push_back({i, w, s});
  std::vector<EpisodeOutcome> results(episodes.size());
  const ValidationEpisodes problem(task, individuals, worlds, episodes, results);
  std::vector<Candidate> batch(episodes.size());
  for (std::size_t k = 0; k < batch.size(); ++k) {
    batch[k].id = k;
    batch[k].genome.reals = {static_cast<double>(k)};
  }
  std::size_t done = 0;
  const ReportFn report = [&](std::size_t, EvaluationOutcome) {
    ++done;
    if (options.progress) options.progress(done, batch.size());
  };
  if (options.jobs > 1) {
    ThreadPoolEvaluator evaluator(options.jobs);
    evaluator.evaluate(problem, batch, report);
  } else {
    SerialEvaluator evaluator;
    evaluator.evaluate(problem, batch, report);
  }
  // Group the outcomes: [individual][world] -> the seeds' outcomes in seed order.
  std::vector<std::vector<std::vector<EpisodeOutcome>>> grouped(
      individuals.size(), std::vector<std::vector<EpisodeOutcome>>(worlds.size()));
  for (std::size_t k = 0; k < episodes.size(); ++k)
    grouped[episodes[k].individual][episodes[k].world].push_back(std::move(results[k]));
  out = summarise_validation(subject.dir, task.config(), individuals, worlds, grouped);
  return {};
}

Status write_validation_file(const fs::path& dir, const json& result) {
  return core::write_file_atomically(dir / "validation.json", result.dump(1) + "\n");
}

std::function<void(std::size_t, std::size_t)> validation_progress_printer(bool terminal) {
  auto last_tenth = std::make_shared<std::size_t>(0);
  return [terminal, last_tenth](std::size_t done, std::size_t total) {
    if (terminal) {
      std::fprintf(stderr, "\rvalidate: %zu/%zu episodes", done, total);
      if (done == total) std::fprintf(stderr, "\n");
      return;
    }
    const std::size_t tenth = total > 0 ? done * 10 / total : 10;
    if (tenth > *last_tenth || done == total) {
      if (tenth == *last_tenth && done != total) return;
      *last_tenth = tenth;
      std::fprintf(stderr, "validate: %zu/%zu episodes\n", done, total);
    }
  };
}

}  // namespace stride::opt
