// The walk task's own settings (walk_task.cpp parses and writes them: config fields
// `goal_distance_m`, `walk_vx` and the straightness limits), held in TaskConfig::own.
#pragma once

#include "stride/optimiser/tasks/straightness_limits.hpp"

namespace stride::opt {

struct WalkSettings {
  double goal_distance_m = 2.5;     ///< the episode ends once covered (> 0)
  double walk_vx = 1.0;             ///< normalised forward command, [-1, 1]
  StraightnessLimits straightness;  ///< max_turn_translation_m unread: the walk does not turn
  bool operator==(const WalkSettings&) const = default;
};

}  // namespace stride::opt
