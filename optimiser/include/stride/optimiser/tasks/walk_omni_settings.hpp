// The walk-omni task's own settings (walk_omni_task.cpp parses and writes them: config field
// `omni` {start_s, ramp_s, hold_s, stop_s} and the straightness limits), held in TaskConfig::own.
#pragma once

#include "stride/optimiser/tasks/straightness_limits.hpp"

namespace stride::opt {

/// The segments of the omnidirectional walk task (walk-omni): after start_s of walking in
/// place from standing, six segments (forward, backward, left, right, turn left, turn right),
/// each a command ramp from 0 to full over ramp_s, a hold of hold_s (where the speed is
/// measured) and a stop (command 0) of stop_s. Episode length start_s + 6 (ramp + hold + stop).
struct OmniTiming {
  double start_s = 4.0;
  double ramp_s = 1.0;
  double hold_s = 8.0;
  double stop_s = 2.0;
  double total_s() const { return start_s + 6.0 * (ramp_s + hold_s + stop_s); }
  bool operator==(const OmniTiming&) const = default;
};

struct OmniSettings {
  OmniTiming timing;  ///< config `omni`
  StraightnessLimits straightness;
  bool operator==(const OmniSettings&) const = default;
};

}  // namespace stride::opt
