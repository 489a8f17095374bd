// The own figures of the tasks that walk in every direction (walk-omni, walk-ramp; they write
// them, TaskFigures in EpisodeScore::figures): per direction the speed and straightness, as the
// run's report (direction_speeds.hpp) and the validation show them, and how merged and shown.
#pragma once

#include <string>
#include <vector>

#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/optimiser/tasks/walk_measures.hpp"

namespace stride::opt {

struct DirectionFigures {
  OmniSegments segments{};  ///< per OmniDirection; a direction not walked is unmeasured, speed 0
  double distance_m = 0.0;  ///< the torso's travel along world x (the report's outcome note)
};

/// Folds the next episode's figures into a world's: each episode fills its own directions
/// (walk-ramp: one per episode), the distance stays the first episode's.
void merge_direction_figures(const TaskFigures& next, TaskFigures& total);
/// The mean speed per direction over a world's seeds: the cell's `speeds` {forward: .., ...}
/// and the table row's one field per direction.
ValidationFigures direction_validation_figures(const std::vector<const EpisodeScore*>& seeds);
/// Every direction was measured: the validation success of a direction task.
bool every_direction_measured(const EpisodeScore& score);
/// The report's note: travel_note of the episode's distance.
std::string direction_outcome_note(const EpisodeScore& score, double end_s);

}  // namespace stride::opt
