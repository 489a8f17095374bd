// EpisodeScore: the raw figures of one task episode (objectives, constraints and what they were
// computed from), for the optimiser, the reports, the validation and the tests. It holds what
// every task shares; a task's own figures (the walk's time to the goal, the kick's ball
// distance, ...) are in `figures`, as that task's struct (task_figures.hpp).
#pragma once

#include <string>
#include <vector>

#include "stride/optimiser/tasks/task_figures.hpp"

namespace stride::opt {

/// The raw figures of one episode (for reports and tests).
struct EpisodeScore {
  std::vector<double> objectives;
  std::vector<double> constraints;
  bool fell = false;
  double max_accel = 0.0;  ///< peak |a| of the IMU [m/s^2]
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;   ///< the episode loop (controller + physics + metrics) [s]
  double setup_s = 0.0;       ///< building the firmware and the world, flashing the genome [s]
  double controller_s = 0.0;  ///< inside Controller::step over the episode [s]
  /// The task's own figures: its struct (walk_figures.hpp, kick_figures.hpp, ...), written by
  /// its episode (TaskEpisode::score) and merged by its type (TaskType::merge_figures).
  TaskFigures figures;
  /// Empty, or why the world failed (NaN, explosion, integrator): run_world() then scores the
  /// episode as a fall at that moment; run_trial() returns it as an error.
  std::string world_failure;
};

}  // namespace stride::opt
