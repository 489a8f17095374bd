// The walk task's own settings (walk_task.cpp parses and writes them: config fields
// `goal_distance_m`, `walk_vx`), held in TaskConfig::own.
#pragma once

namespace stride::opt {

struct WalkSettings {
  double goal_distance_m = 2.5;  ///< the episode ends once covered (> 0)
  double walk_vx = 1.0;          ///< normalised forward command, [-1, 1]
  bool operator==(const WalkSettings&) const = default;
};

}  // namespace stride::opt
