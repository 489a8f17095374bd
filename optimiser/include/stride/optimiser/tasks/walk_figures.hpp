// The walk task's own figures of an episode (walk_task.cpp writes them; TaskFigures in
// EpisodeScore::figures): how far it went, when it reached the goal, how straight it walked.
#pragma once

namespace stride::opt {

struct WalkFigures {
  double distance_m = 0.0;       ///< the torso's travel along world x [m]
  double time_to_goal_s = -1.0;  ///< when goal_distance_m was covered [s] (-1: never)
  // Straightness at the goal (or the episode's end), in the start's walking frame
  // (walk_measures.hpp).
  double lateral_drift_m = 0.0;
  double heading_change_rad = 0.0;
};

}  // namespace stride::opt
