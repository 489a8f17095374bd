// The walk-command task's settings (task "walk-command", issue 53 point 2; the task itself is
// optimiser/src/tasks/walk_command_task.cpp, which parses and writes them: config field
// `command` and the straightness limits), held in TaskConfig::own (CommandSettings).
//
// One episode per world, from standing: a walk request with zero command at tick 0 (stepping in
// place) for start_s, then the segments in order, each a normalised walk command (vx, vy,
// vtheta) held for hold_s, or a stand request held for stop_s. A walk segment's figures are
// measured over its last measure_s from ground truth (walk_measures.hpp), a translation along
// the direction the walk plans for its command (ramp_command.hpp: the command's axis, or for a
// diagonal where the genome's own limits send it); a stand segment's is whether the motion
// manager stands at its end. The six directions (segments named forward,
// backward, left, right, turn_left, turn_right, each once, commanding that direction) score the
// speed objective against the reference speeds (kReferenceSpeeds).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/optimiser/tasks/straightness_limits.hpp"

namespace stride::opt {

/// One segment of the schedule.
struct CommandSegmentSpec {
  std::string name;
  std::array<double, 3> command{0.0, 0.0, 0.0};  ///< normalised (vx, vy, vtheta), each in [-1, 1]
  bool stand = false;                            ///< a stand request for stop_s instead
  bool operator==(const CommandSegmentSpec&) const = default;
};

/// The default schedule: the six directions (a reversal between forward and backward), a curve
/// (walk and turn), a diagonal, then a stop (stand), a restart forward and a reversal.
std::vector<CommandSegmentSpec> default_command_segments();

struct CommandSchedule {
  double start_s = 2.0;    ///< stepping in place before the first segment [s]
  double hold_s = 4.0;     ///< each walk segment [s]
  double measure_s = 2.5;  ///< a walk segment's last seconds, where it is measured [s]
  double stop_s = 1.5;     ///< each stand segment [s]
  std::vector<CommandSegmentSpec> segments = default_command_segments();
  /// The episode's length [s]: 43.5 s by default.
  double total_s() const;
  /// The start of segment `k` [s] (k == segments.size(): the end).
  double begin_s(std::size_t k) const;
  bool operator==(const CommandSchedule&) const = default;
};

/// The walk-command task's own settings (TaskConfig::own).
struct CommandSettings {
  CommandSchedule schedule;  ///< config `command`
  StraightnessLimits straightness;
  bool operator==(const CommandSettings&) const = default;
};

/// Reads the config's `command` object over `out`'s values; the error names the field
/// ("command.segments[2].command: ...") and leaves `out` unchanged.
Status parse_command_schedule(const nlohmann::json& doc, CommandSchedule& out);
/// Every field, so that a run.json rebuilds the same schedule whatever the defaults become.
nlohmann::json to_json(const CommandSchedule& schedule);

}  // namespace stride::opt
