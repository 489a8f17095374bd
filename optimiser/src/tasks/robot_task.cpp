// RobotTask: the firmware against the simulated robot, in the episodes of the config's task type.
#include "stride/optimiser/tasks/robot_task.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>

#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::opt {

namespace {

/// The config's world with the trial's engine, seed, noise and randomisation (robot_task.hpp).
sim::WorldSpec trial_world_spec(const TaskConfig& config, int world, std::uint64_t draw) {
  sim::WorldSpec spec = config.world;
  const int trial = world % config.trials;
  spec.engine =
      config.engines[static_cast<std::size_t>(world / config.trials) % config.engines.size()];
  spec.seed = trial_world_seed(config, trial, draw);
  // One trial is the nominal world, unless the run draws its worlds again each generation
  // (resample): a nominal world cannot be drawn again, so then it is one randomised world.
  const bool randomised = config.trials > 1 || config.settings.resample;
  spec.noise = randomised && config.randomisation.imu_noise;
  spec.randomise = randomised ? sim::Randomisation(config.randomisation) : sim::Randomisation{};
  return spec;
}

/// The world `spec` names with what the task type adds: no ball unless the task kicks one.
sim::WorldOptions task_world_options(const TaskConfig& config, const sim::WorldSpec& spec) {
  sim::WorldOptions w = spec.to_options();
  const TaskType* type = find_task_type(config.task);
  if (type == nullptr || !type->descriptor().uses_ball) w.ball.present = false;
  return w;
}

sim::WorldOptions world_for_trial(const TaskConfig& config, int world, std::uint64_t draw) {
  return task_world_options(config, trial_world_spec(config, world, draw));
}

/// The simulated world of this thread on `kind`'s engine: made by the first episode the thread
/// runs there, then restarted for every later one (SimWorld::restart gives the bits of a new
/// world), so that the engine builds what it can once per worker and not once per episode.
std::unique_ptr<sim::SimWorld>& thread_world(sim::EngineKind kind) {
  thread_local std::array<std::unique_ptr<sim::SimWorld>, 2> worlds;
  return worlds[static_cast<std::size_t>(kind) % worlds.size()];
}

/// This thread's world restarted as `options` and `spec` (made if the thread has none).
Status restart_thread_world(const sim::WorldOptions& options, const sim::ResetSpec& spec,
                            std::unique_ptr<sim::SimWorld>& out) {
  std::unique_ptr<sim::SimWorld>& world = thread_world(options.engine);
  Status s = world ? world->restart(options, spec) : sim::SimWorld::create(options, spec, world);
  if (!s) {
    world.reset();  // a failed restart leaves nothing to reuse
    return s;
  }
  out = std::move(world);
  return s;
}

}  // namespace

std::uint64_t trial_world_seed(const TaskConfig& config, int trial, std::uint64_t draw) {
  return config.trial_seed + draw * kDrawSeedSpacing + static_cast<std::uint64_t>(trial);
}

RobotTask::RobotTask(TaskConfig config)
    : config_(std::move(config)), type_(find_task_type(config_.task)) {
  for (const auto& g : config_.genes) shape_.reals.push_back({g.min, g.max});
  shape_.objectives = 2;
  shape_.constraints = type_ != nullptr ? type_->descriptor().constraint_count : 0;
  auto files = std::make_shared<fw::FirmwareFiles>();
  if (fw::FirmwareFiles::load({}, *files)) {
    firmware_files_ = std::move(files);
    std::unique_ptr<fw::Firmware> firmware;
    if (fw::Firmware::create({}, *firmware_files_, firmware))
      control_period_ns_ = firmware->period_ns();
  }
  if (config_.world.model != nullptr) {
    robot_model_ = config_.world.model;
  } else {
    auto model = std::make_shared<sim::RobotModel>();
    const std::filesystem::path urdf =
        config_.world.urdf.empty() ? sim::WorldOptions{}.urdf : config_.world.urdf;
    if (sim::RobotModel::load_file(urdf, *model)) robot_model_ = std::move(model);
  }
}

Status RobotTask::check() const {
  if (type_ == nullptr)
    return Status::error("task: '" + config_.task + "' is not " + task_type_list());
  if (control_period_ns_ <= 0) {
    std::unique_ptr<fw::Firmware> firmware;
    if (Status s = fw::Firmware::create({}, firmware); !s) return s;
  }
  if (Status s = sim::check_physics_step(config_.world.physics_step_us * 1000, control_period_ns_);
      !s)
    return s;
  return type_->check(config_);
}

Genome RobotTask::start_genome() const {
  Genome g;
  for (const auto& gene : config_.genes) g.reals.push_back(gene.start);
  return g;
}

Status RobotTask::extra_start_genomes(std::vector<Genome>& out) const {
  out.clear();
  std::unique_ptr<fw::Firmware> firmware;  // the registered defaults, for "defaults"
  for (std::size_t k = 0; k < config_.starts.size(); ++k) {
    const TaskConfig::Start& start = config_.starts[k];
    const std::string field = "starts[" + std::to_string(k) + "]";
    if (start.firmware_defaults && firmware == nullptr) {
      if (Status s = firmware_files_ ? fw::Firmware::create({}, *firmware_files_, firmware)
                                     : fw::Firmware::create({}, firmware);
          !s)
        return Status::error(field + ": " + s.message());
    }
    Genome g = start_genome();
    for (std::size_t i = 0; i < config_.genes.size(); ++i) {
      const TaskGene& gene = config_.genes[i];
      if (start.firmware_defaults) {
        if (Status s = firmware->params().get(gene.parameter, g.reals[i]); !s)
          return Status::error(field + ": " + s.message());
      }
      for (const auto& [name, value] : start.values)
        if (name == gene.parameter) g.reals[i] = value;
      if (!(g.reals[i] >= gene.min && g.reals[i] <= gene.max))
        return Status::error(field + ": " + gene.parameter + " = " + std::to_string(g.reals[i]) +
                             " is outside the gene's range [" + std::to_string(gene.min) + ", " +
                             std::to_string(gene.max) + "]");
    }
    out.push_back(std::move(g));
  }
  return {};
}

nlohmann::json RobotTask::parameter_file(const Genome& genome) const {
  nlohmann::json doc = nlohmann::json::object();
  for (std::size_t i = 0; i < config_.genes.size() && i < genome.reals.size(); ++i)
    doc[config_.genes[i].parameter] = genome.reals[i];
  return doc;
}

std::optional<FrontReference> RobotTask::reference() const {
  if (config_.hv_ideal.empty()) return std::nullopt;
  FrontReference r;
  r.ideal = config_.hv_ideal;
  r.nadir = config_.hv_nadir;
  return r;
}

sim::WorldSpec RobotTask::world_spec(int world, std::uint64_t draw) const {
  return trial_world_spec(config_, world, draw);
}

sim::WorldOptions RobotTask::world_options(const sim::WorldSpec& spec) const {
  return task_world_options(config_, spec);
}

sim::WorldOptions RobotTask::world_options(int world, std::uint64_t draw) const {
  return world_for_trial(config_, world, draw);
}

Status RobotTask::run_trial(const Genome& genome, int world, EpisodeScore& out,
                            sim::EpisodeCapturer* capture) const {
  if (Status s = run_world(genome, world_for_trial(config_, world, 0), out, capture); !s) return s;
  if (!out.world_failure.empty()) return Status::error("simulation: " + out.world_failure);
  return {};
}

Status RobotTask::run_world(const Genome& genome, sim::WorldOptions options, EpisodeScore& out,
                            sim::EpisodeCapturer* capture) const {
  const int episodes = type_ != nullptr ? type_->descriptor().episodes_per_world : 1;
  for (int e = 0; e < episodes; ++e) {
    EpisodeScore score;
    if (Status s = run_world_episode(genome, options, e, score, e == 0 ? capture : nullptr); !s)
      return s;
    if (e == 0) {
      out = std::move(score);
      continue;
    }
    merge_episode(score, e + 1, out);
  }
  return {};
}

Status RobotTask::run_world_episode(const Genome& genome, sim::WorldOptions options, int episode,
                                    EpisodeScore& out, sim::EpisodeCapturer* capture) const {
  if (type_ == nullptr) return Status::error("task: '" + config_.task + "' is not a robot task");
  if (genome.reals.size() != config_.genes.size())
    return Status::error("genome has " + std::to_string(genome.reals.size()) + " genes, the task " +
                         std::to_string(config_.genes.size()));
  if (options.urdf == (config_.world.urdf.empty() ? sim::WorldOptions{}.urdf : config_.world.urdf))
    options.model = robot_model_;
  return run_episode(genome, options, episode, out, capture);
}

Status RobotTask::run_episode(const Genome& genome, const sim::WorldOptions& options, int index,
                              EpisodeScore& out, sim::EpisodeCapturer* capture) const {
  using Clock = std::chrono::steady_clock;
  const auto setup_start = Clock::now();
  std::unique_ptr<fw::Firmware> firmware;
  if (Status s = firmware_files_ ? fw::Firmware::create({}, *firmware_files_, firmware)
                                 : fw::Firmware::create({}, firmware);
      !s)
    return s;
  sim::WorldOptions world_options = options;
  world_options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  if (Status s = restart_thread_world(world_options, type_->reset_spec(config_, index), world); !s)
    return s;
  sim::SimRobot robot(std::move(world));
  // The world goes back to the thread when the episode ends, whichever way it ends.
  struct GiveBack {
    sim::SimRobot& robot;
    sim::EngineKind engine;
    ~GiveBack() { thread_world(engine) = robot.release_world(); }
  } give_back{robot, world_options.engine};

  // The config's base parameters first (set now: the firmware's start-up values), then the
  // genome: one validated batch, staged, applied atomically at tick 0.
  fw::ParameterStore& params = firmware->params();
  fw::Controller& controller = firmware->controller();
  const double period_s = static_cast<double>(robot.period_ns()) * 1e-9;
  const std::unique_ptr<TaskEpisode> task_episode =
      type_->start_episode(config_, index, period_s, robot.world());
  sim::EpisodeOptions episode = task_episode->options();
  // An episode that ends at the fall scores the motion up to the fall, not the landing: the
  // fall protection (fall.protect, firmware/src/FALLING.md) is off there, so that a predicted
  // fall plays out as it did before the protection existed (the scores and the exactness
  // hashes of tests/integration/optimiser stay bit for bit). A config may still set it.
  if (episode.stop_on_fall) {
    if (Status s = params.set_now({{"fall.protect", 0.0}}); !s) return s;
  }
  if (!config_.base_params.empty()) {
    if (Status s = params.set_now(config_.base_params); !s)
      return Status::error("params: " + s.message());
  }
  std::vector<fw::ParamWrite> batch;
  for (std::size_t i = 0; i < config_.genes.size(); ++i)
    batch.push_back({config_.genes[i].parameter, genome.reals[i]});
  if (Status s = params.stage(batch); !s) return s;

  double controller_s = 0.0;
  const double setup_s = std::chrono::duration<double>(Clock::now() - setup_start).count();
  bool first_tick = true;
  const sim::StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    params.apply_staged();
    if (first_tick) task_episode->parameters_applied(params);
    first_tick = false;
    task_episode->before_step(sensors, tick, robot.world(), controller);
    const auto before = Clock::now();
    hal::CommandFrame commands = controller.step(sensors, tick);
    controller_s += std::chrono::duration<double>(Clock::now() - before).count();
    task_episode->after_step(controller, robot.world(), tick);
    return commands;
  };
  if (capture != nullptr) episode.on_tick = capture->observer();
  sim::EpisodeResult r = sim::run_episode(robot, step, episode);
  if (params.has_staged()) return Status::error("the genome was never applied");
  // A failed world ends the episode: scored below as a fall at that moment.
  const bool failed = r.status != sim::WorldStatus::kRunning;
  if (failed && !r.fell) {
    r.fell = true;
    r.fall_time_s = r.sim_time_s;
    r.time_to_goal_s.reset();
  }

  out = {};
  if (failed)
    out.world_failure =
        r.failure_reason.empty() ? std::string(sim::to_string(r.status)) : r.failure_reason;
  out.fell = r.fell;
  out.max_accel = r.max_accel;
  out.sim_time_s = r.sim_time_s;
  out.wall_time_s = r.wall_time_s;
  out.setup_s = setup_s;
  out.controller_s = controller_s;
  return task_episode->score(r, robot.world(), controller, out);
}

void RobotTask::merge_episode(const EpisodeScore& next, int count, EpisodeScore& total) const {
  // Running means of the values (count = episodes so far, `next` included).
  const double w = 1.0 / count;
  for (std::size_t i = 0; i < total.objectives.size() && i < next.objectives.size(); ++i)
    total.objectives[i] += (next.objectives[i] - total.objectives[i]) * w;
  for (std::size_t i = 0; i < total.constraints.size() && i < next.constraints.size(); ++i)
    total.constraints[i] += (next.constraints[i] - total.constraints[i]) * w;
  total.fell = total.fell || next.fell;
  total.max_accel = std::max(total.max_accel, next.max_accel);
  total.sim_time_s += next.sim_time_s;
  total.wall_time_s += next.wall_time_s;
  total.setup_s += next.setup_s;
  total.controller_s += next.controller_s;
  if (total.world_failure.empty()) total.world_failure = next.world_failure;
  if (type_ != nullptr) type_->merge_figures(next.figures, count, total.figures);
}

namespace {

/// One episode of an evaluation (a part): its score, or why it could not run.
struct EpisodePart final : PartResult {
  Status status;
  EpisodeScore score;
};

}  // namespace

std::size_t RobotTask::part_count(const Genome&) const {
  const int episodes = type_ != nullptr ? type_->descriptor().episodes_per_world : 1;
  return static_cast<std::size_t>(config_.world_count()) * static_cast<std::size_t>(episodes);
}

std::unique_ptr<PartResult> RobotTask::evaluate_part(const Genome& genome, std::size_t part,
                                                     std::uint64_t draw) const {
  auto out = std::make_unique<EpisodePart>();
  const int episodes = type_ != nullptr ? type_->descriptor().episodes_per_world : 1;
  const int world = static_cast<int>(part / static_cast<std::size_t>(episodes));
  const int episode = static_cast<int>(part % static_cast<std::size_t>(episodes));
  out->status =
      run_world_episode(genome, world_for_trial(config_, world, draw), episode, out->score);
  return out;
}

EvaluationOutcome RobotTask::fold_parts(const Genome&,
                                        std::vector<std::unique_ptr<PartResult>>& parts) const {
  const int worlds = config_.world_count();
  const int episodes = type_ != nullptr ? type_->descriptor().episodes_per_world : 1;
  if (parts.size() != static_cast<std::size_t>(worlds) * static_cast<std::size_t>(episodes))
    return EvaluationOutcome::failure(std::to_string(parts.size()) + " episodes for " +
                                      std::to_string(worlds) + " worlds of " +
                                      std::to_string(episodes));
  EvaluationOutcome outcome;
  for (int k = 0; k < worlds; ++k) {
    // The world's episodes merged in order, as run_world() does.
    EpisodeScore score;
    for (int e = 0; e < episodes; ++e) {
      auto* part = dynamic_cast<EpisodePart*>(
          parts[static_cast<std::size_t>(k) * static_cast<std::size_t>(episodes) +
                static_cast<std::size_t>(e)]
              .get());
      if (part == nullptr)
        return EvaluationOutcome::failure("trial " + std::to_string(k) +
                                          ": an episode gave no result");
      if (!part->status)
        return EvaluationOutcome::failure("trial " + std::to_string(k) + ": " +
                                          part->status.message());
      if (e == 0) {
        score = std::move(part->score);
        continue;
      }
      merge_episode(part->score, e + 1, score);
    }
    if (!score.world_failure.empty())
      return EvaluationOutcome::failure("trial " + std::to_string(k) +
                                        ": simulation: " + score.world_failure);
    if (k == 0) {
      outcome.objectives = score.objectives;
      outcome.constraints = score.constraints;
      continue;
    }
    for (std::size_t i = 0; i < score.objectives.size(); ++i)
      outcome.objectives[i] = config_.aggregate == Aggregate::kMean
                                  ? outcome.objectives[i] + score.objectives[i]
                                  : std::max(outcome.objectives[i], score.objectives[i]);
    for (std::size_t i = 0; i < score.constraints.size(); ++i)
      outcome.constraints[i] = config_.aggregate == Aggregate::kMean
                                   ? outcome.constraints[i] + score.constraints[i]
                                   : std::min(outcome.constraints[i], score.constraints[i]);
  }
  if (config_.aggregate == Aggregate::kMean && worlds > 1) {
    const double n = worlds;
    for (double& v : outcome.objectives) v /= n;
    for (double& v : outcome.constraints) v /= n;
  }
  return outcome;
}

EvaluationOutcome RobotTask::evaluate(const Genome& genome) const {
  return evaluate_on(genome, 0);
}

EvaluationOutcome RobotTask::evaluate_on(const Genome& genome, std::uint64_t draw) const {
  // The parts one after the other, folded as an evaluator folds them.
  std::vector<std::unique_ptr<PartResult>> parts;
  const std::size_t count = part_count(genome);
  for (std::size_t k = 0; k < count; ++k) parts.push_back(evaluate_part(genome, k, draw));
  return fold_parts(genome, parts);
}

}  // namespace stride::opt
