// EpisodeScore: the raw figures of one task episode (objectives, constraints and what they were
// computed from), for the optimiser, the reports, the validation and the tests. A task's own
// figures go in `figures`, as that task's struct (task_figures.hpp).
#pragma once

#include <string>
#include <vector>

#include "stride/optimiser/tasks/task_figures.hpp"
#include "stride/optimiser/tasks/walk_measures.hpp"

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
  // getup: over the world's episodes (from the front and from the back).
  double stand_time_s = -1.0;  ///< mean time until standing again (-1: not every episode stood)
  int stood = 0;               ///< episodes that ended standing
  int get_up_attempts = 0;     ///< get-up scripts started, summed over the episodes
  /// The task's own figures: its struct (walk_figures.hpp, kick_figures.hpp, ...), written by
  /// its episode (TaskEpisode::score) and merged by its type (TaskType::merge_figures).
  TaskFigures figures;
  /// Empty, or why the world failed (NaN, explosion, integrator): run_world() then scores the
  /// episode as a fall at that moment; run_trial() returns it as an error.
  std::string world_failure;
};

}  // namespace stride::opt
