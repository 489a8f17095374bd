// RobotTask: a robot optimisation task (TaskType, task_type.hpp: walk, walk-omni, kick, getup)
// as an NSGA-II problem.
//
// One evaluation = `trials` x engines worlds (TaskConfig::world_count), each of the task's
// episodes_per_world() episodes. Each episode builds a simulated world (SimWorld on the world's
// engine, seeded with trial_world_seed(); trial 0 of a single-trial task is the nominal world,
// robust trials randomise friction, masses, servo strength and IMU noise) and a Firmware, resets
// the world to the task's start, stages the genome into the firmware's ParameterStore
// (ParameterStore::stage, the console's atomic write; it takes effect at tick 0 through
// apply_staged, as in the ControlLoop), and runs the unmodified Controller against SimRobot in
// lockstep (sim::run_episode) with the task's requests; the task scores the episode. The
// objectives and constraints of each task are in its file (optimiser/src/tasks/*_task.cpp).
// Worlds are aggregated per value by mean or worst (max objective, min constraint).
// Each episode is one part of the evaluation (Problem::part_count), so that a thread pool spreads
// the episodes of a whole batch over its workers; folding them in part order gives the same
// outcome whatever the thread count. Each worker thread keeps one SimWorld per engine, made by
// its first episode and restarted for the next ones (SimWorld::restart: the bits of a new
// world), and every firmware is private to its episode, so evaluate() is thread-safe and the
// outcome depends on the genome alone. The files they are built from (servo table, keyframe
// scripts, URDF) are read once, when the task is made, and shared read-only.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "stride/firmware/firmware.hpp"
#include "stride/optimiser/nsga2/problem.hpp"
#include "stride/optimiser/tasks/episode_score.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/optimiser/tasks/walk_measures.hpp"
#include "stride/sim_hal/episode_capture.hpp"
#include "stride/sim_hal/robot_model.hpp"

namespace stride::opt {

/// Seed spacing of the draws: draw d's K trial worlds are seeded trial_seed + d * 10^6 + k
/// (k < K <= 1000), so no two draws share a world, and none meets stride validate's seeds
/// (trial_seed + 1000 + i, i < 1000). Draw 0 is the fixed trials of a run without resampling;
/// kRescoreDraw (settings.hpp) the fresh worlds a resampling run's final front is scored on.
inline constexpr std::uint64_t kDrawSeedSpacing = 1'000'000;
/// The seed of trial `trial` of draw `draw`.
std::uint64_t trial_world_seed(const TaskConfig& config, int trial, std::uint64_t draw);

class RobotTask final : public Problem {
 public:
  explicit RobotTask(TaskConfig config);
  std::string name() const override { return config_.task; }
  const ProblemShape& shape() const override { return shape_; }
  /// evaluate_on(genome, 0): the trial worlds of draw 0.
  EvaluationOutcome evaluate(const Genome& genome) const override;
  /// The genome in the trial worlds of draw `draw` (trial_world_seed).
  EvaluationOutcome evaluate_on(const Genome& genome, std::uint64_t draw) const override;
  std::optional<FrontReference> reference() const override;
  /// One part per episode: world_count() worlds x the task's episodes_per_world(), world-major.
  std::size_t part_count(const Genome& genome) const override;
  std::unique_ptr<PartResult> evaluate_part(const Genome& genome, std::size_t part,
                                            std::uint64_t draw) const override;
  /// Each world's episodes merged in order, then the worlds aggregated: evaluate()'s outcome.
  EvaluationOutcome fold_parts(const Genome& genome,
                               std::vector<std::unique_ptr<PartResult>>& parts) const override;

  const TaskConfig& config() const { return config_; }
  /// The task against the firmware it runs, before any episode: a robot task's name, and a
  /// physics step that divides the firmware's control period (sim::check_physics_step; the
  /// error names physics_step_us).
  Status check() const;
  /// The control period of the firmware the episodes run [ns] (0 if it could not be built).
  std::int64_t control_period_ns() const { return control_period_ns_; }
  /// The config's task type (null if its name is not a robot task's).
  const TaskType* type() const { return type_; }
  /// The start genome (Ind_O: every gene's start value).
  Genome start_genome() const;
  /// The config's further starts (TaskConfig::starts) as genomes; the error names the start
  /// and the gene whose value lies outside the gene's range.
  Status extra_start_genomes(std::vector<Genome>& out) const;
  /// World `world` (0-based, < config().world_count()) of draw `draw` as options by name: the
  /// config's world with the trial's engine, seed, noise and randomisation (trial 1 of 1 is the
  /// nominal world: no noise, no randomisation, unless the run resamples; K > 1 trials, and the
  /// one trial of a resampling run, are randomised worlds).
  sim::WorldSpec world_spec(int world, std::uint64_t draw = 0) const;
  /// The world `spec` names as the task's episodes run it: spec.to_options() and what the task
  /// type adds (no ball unless the task uses one). Validation worlds are made with it too.
  sim::WorldOptions world_options(const sim::WorldSpec& spec) const;
  /// world_options(world_spec(world, draw)).
  sim::WorldOptions world_options(int world, std::uint64_t draw = 0) const;
  /// The robot the episodes run (the config world's URDF, else the igus model); null if it
  /// could not be loaded.
  const std::shared_ptr<const sim::RobotModel>& robot_model() const { return robot_model_; }
  /// One episode in world `world` (0-based); a failure reason on a broken set-up or world.
  /// `capture`, if given, observes every tick (replays in `stride report`); it changes nothing.
  Status run_trial(const Genome& genome, int world, EpisodeScore& out,
                   sim::EpisodeCapturer* capture = nullptr) const;
  /// One episode in any world (validation). A world that fails mid-episode (NaN, explosion)
  /// is not an error: the score is a fall at that moment with `world_failure` set. Errors are
  /// a set-up that cannot be built (engine, model, genome refused).
  Status run_world(const Genome& genome, sim::WorldOptions world, EpisodeScore& out,
                   sim::EpisodeCapturer* capture = nullptr) const;
  /// The genome as a parameter file body {"name": value, ...} (loadable by --params).
  nlohmann::json parameter_file(const Genome& genome) const;

 private:
  TaskConfig config_;
  ProblemShape shape_;
  // Loaded by the constructor; null if loading failed, and then every run_trial loads the
  // files itself and reports the error.
  std::shared_ptr<const fw::FirmwareFiles> firmware_files_;
  std::shared_ptr<const sim::RobotModel> robot_model_;
  const TaskType* type_ = nullptr;  ///< null: not a robot task (every episode is an error)
  std::int64_t control_period_ns_ = 0;

  /// Episode `episode` of the task in `options`' world, with the task's shared robot model.
  Status run_world_episode(const Genome& genome, sim::WorldOptions options, int episode,
                           EpisodeScore& out, sim::EpisodeCapturer* capture = nullptr) const;
  Status run_episode(const Genome& genome, const sim::WorldOptions& options, int index,
                     EpisodeScore& out, sim::EpisodeCapturer* capture) const;
  /// Folds episode `count` (1-based) of a world into the world's score so far: the shared
  /// figures here, the task's own by its type (TaskType::merge_figures).
  void merge_episode(const EpisodeScore& next, int count, EpisodeScore& total) const;
};

}  // namespace stride::opt
