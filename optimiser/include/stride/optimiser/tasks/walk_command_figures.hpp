// The walk-command task's own figures of an episode (TaskFigures in EpisodeScore::figures,
// written by walk_command_task.cpp): per segment of the schedule (walk_command_settings.hpp) the
// realised speed, turn rate and straightness over its measurement window, or whether a stand
// segment ended standing.
#pragma once

#include <string>
#include <vector>

#include "stride/optimiser/tasks/walk_measures.hpp"

namespace stride::opt {

/// One segment's figures. A segment not reached before a fall is unmeasured with speed 0.
struct CommandSegmentFigures {
  std::string name;
  bool stand = false;               ///< a stand segment (only `stood` applies)
  bool measured = false;            ///< the segment was completed
  double speed = 0.0;               ///< along the commanded axis [m/s]; turns: turn rate [rad/s]
  double turn_rate_radps = 0.0;     ///< yaw rate the commanded way (segments that turn) [rad/s]
  double drift_ratio = 0.0;         ///< off-axis / max(|along|, floor) (segments that translate)
  double heading_change_rad = 0.0;  ///< |yaw change| over the window
  double translation_m = 0.0;       ///< |displacement| over the window
  bool stood = false;               ///< stand segments: the motion manager stood at its end
};

struct CommandFigures {
  std::vector<CommandSegmentFigures> segments;  ///< in schedule order
  OmniSegments directions{};  ///< the six directions' segments (speed, straightness)
  double distance_m = 0.0;    ///< the torso's travel along world x (the report's outcome note)
};

}  // namespace stride::opt
