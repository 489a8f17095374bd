// The speed-ramp walk task's settings (task "walk-ramp", issue 32 point 1; the task itself is
// optimiser/src/tasks/walk_ramp_task.cpp).
//
// Per direction (forward, backward, left, right, turn left, turn right; one episode each, from
// standing): after start_s of walking in place, the command rises by `increment` (normalised,
// of the walk engine's limits) every hold_s, up to max_levels levels. A level's speed is
// measured over its last measure_s from ground truth (the walking frame, walk_measures.hpp).
// The direction ends at a fall, when `patience` levels in a row are no faster than the best so
// far ("stops rising"; the feet's step-to-step sway makes one level's figure noisy), or when
// the drift or heading change since its first level is beyond the straightness limits (for a
// turn: the level's translation); its score is the best speed held.
#pragma once

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"

namespace stride::opt {

struct RampTiming {
  double start_s = 2.0;    ///< walking in place before the first level [s]
  double increment = 0.1;  ///< command step per level (normalised, (0, 1])
  double hold_s = 4.0;     ///< each level [s]
  double measure_s = 2.0;  ///< the level's last seconds, where its speed is measured [s]
  int max_levels = 10;     ///< levels per direction (the command reaches max_levels * increment)
  int patience = 2;        ///< levels in a row no faster than the best before a direction ends
  double episode_s() const { return start_s + max_levels * hold_s; }
};

/// Reads the config's `ramp` object; the error names the field ("ramp.hold_s: ...").
Status parse_ramp(const nlohmann::json& doc, RampTiming& out);
nlohmann::json to_json(const RampTiming& ramp);

}  // namespace stride::opt
