// RobotTask: the walk and kick optimisation tasks as NSGA-II problems.
//
// One evaluation = `trials` x engines episodes (TaskConfig::world_count). Each episode builds a
// simulated world (SimWorld on the world's engine, seeded with trial_seed + trial; trial 0 of a
// single-trial task is the nominal world, robust trials randomise friction, masses, servo
// strength and IMU noise) and a Firmware, stages the genome
// into the firmware's ParameterStore (ParameterStore::stage, the console's atomic write; it
// takes effect at tick 0 through apply_staged, as in the ControlLoop), and runs the unmodified
// Controller against SimRobot in lockstep (sim::run_episode).
//
// walk  Obj1 = time to cover goal_distance_m [s]; not reached: duration_s + 10 s/m * the
//       distance still missing (a penalty that still rewards progress).
//       Obj2 = max |a| of the IMU over the episode [m/s^2].
//       c0 = fell ? -(1 + time lost / duration) : 0  (g >= 0 is feasible).
//       Straightness at the goal (or the episode's end), from ground truth (walk_measures.hpp):
//       c1 = min(0, 1 - (|lateral drift| / max(forward, 0.25 m)) / max_drift_ratio),
//       c2 = min(0, 1 - |heading change| / max_heading_change_deg); a limit of null is off.
// walk-omni  six segments forward, backward, sideways both ways, turning both ways;
//       Obj1 = -(v_f + v_b + 2 v_side + 0.2 w_turn), Obj2 = max |a|; c0 fell, c1 drift,
//       c2 heading change, c3 translation while turning (walk_measures.hpp).
// kick  Obj1 = max field-plane sway sqrt(ax^2 + ay^2) [m/s^2] (1000 if fell),
//       Obj2 = 1 / ball distance, distance clamped to [0.001, 10] m (1000 if fell).
//       c0 = fell ? -10 : 0; c1 = -(|integral of gyro z| - limit) when over the limit.
// Worlds are aggregated per value by mean or worst (max objective, min constraint).
// Every world and firmware is private to the call, so evaluate() is thread-safe and the
// outcome depends on the genome alone. The files they are built from (servo table, keyframe
// scripts, URDF) are read once, when the task is made, and shared read-only.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "stride/firmware/firmware.hpp"
#include "stride/optimiser/nsga2/problem.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
#include "stride/optimiser/tasks/walk_measures.hpp"
#include "stride/sim_hal/episode_capture.hpp"
#include "stride/sim_hal/robot_model.hpp"

namespace stride::opt {

/// The raw figures of one episode (for reports and tests).
struct EpisodeScore {
  std::vector<double> objectives;
  std::vector<double> constraints;
  bool fell = false;
  double distance_m = 0.0;
  double time_to_goal_s = -1.0;
  double max_accel = 0.0;
  double max_fps = 0.0;
  double ball_distance_m = 0.0;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;   ///< the episode loop (controller + physics + metrics) [s]
  double setup_s = 0.0;       ///< building the firmware and the world, flashing the genome [s]
  double controller_s = 0.0;  ///< inside Controller::step over the episode [s]
  // walk: straightness at the end, in the start's walking frame (walk_measures.hpp).
  double lateral_drift_m = 0.0;
  double heading_change_rad = 0.0;
  // walk-omni: the segments.
  OmniSegments omni{};
  /// Empty, or why the world failed (NaN, explosion, integrator): run_world() then scores the
  /// episode as a fall at that moment; run_trial() returns it as an error.
  std::string world_failure;
};

class RobotTask final : public Problem {
 public:
  explicit RobotTask(TaskConfig config);
  std::string name() const override { return config_.task; }
  const ProblemShape& shape() const override { return shape_; }
  EvaluationOutcome evaluate(const Genome& genome) const override;
  std::optional<FrontReference> reference() const override;

  const TaskConfig& config() const { return config_; }
  /// The start genome (Ind_O: every gene's start value).
  Genome start_genome() const;
  /// The options of world `world` (0-based, < config().world_count()) of the task.
  sim::WorldOptions world_options(int world) const;
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
};

}  // namespace stride::opt
