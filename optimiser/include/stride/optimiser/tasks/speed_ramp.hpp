// The speed-ramp walk task's settings (task "walk-ramp", issue 32 point 1; the task itself is
// optimiser/src/tasks/walk_ramp_task.cpp, which parses and writes them: config field `ramp` and
// the straightness limits), its own settings held in TaskConfig::own (RampSettings).
//
// Per direction (forward, backward, left, right, turn left, turn right; one episode each, from
// standing): after start_s standing, level k = 1, 2, ... asks for a speed of k * increment_mps
// [m/s] (translations) or k * increment_radps [rad/s] (turns) for hold_s each, up to max_levels
// levels (issue 41 point 3: a level is the same physical speed for every genome). The episode
// turns a level's speed into the walk's normalised command with the walk's own parameters as
// the genome set them (step time, velocity and step limits: ramp_command.hpp has the mapping);
// a level beyond what those limits can command ends the direction. A level's speed is measured
// over its last measure_s from ground truth (the walking frame, walk_measures.hpp). The
// direction also ends at a fall, when `patience` levels in a row are no faster than the best so
// far ("stops rising"; the feet's step-to-step sway makes one level's figure noisy), or when the
// drift or heading change since its first level is beyond the straightness limits (for a turn:
// the level's translation); its score is the best speed held.
//
// The runs of issue 32 ramped the normalised command instead: level k commanded
// min(1, k * increment) of the walk's limits. A `ramp` with `increment` > 0 still does that, so
// that their run.json files resume and validate as they ran.
#pragma once

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/optimiser/tasks/straightness_limits.hpp"

namespace stride::opt {

struct RampTiming {
  double start_s = 2.0;          ///< standing before the first level [s]
  double increment_mps = 0.05;   ///< translation speed added per level [m/s], (0, 1]
  double increment_radps = 0.2;  ///< turning speed added per level [rad/s], (0, 5]
  double increment = 0.0;        ///< issue 32's normalised command per level, [0, 1]; 0: off
  double hold_s = 4.0;           ///< each level [s]
  double measure_s = 2.0;        ///< the level's last seconds, where its speed is measured [s]
  int max_levels = 10;           ///< levels per direction
  int patience = 2;              ///< levels in a row no faster than the best before it ends
  double episode_s() const { return start_s + max_levels * hold_s; }
  /// Levels of normalised command (issue 32's runs) rather than of speed.
  bool normalised() const { return increment > 0.0; }
  bool operator==(const RampTiming&) const = default;
};

/// The walk-ramp task's own settings (TaskConfig::own).
struct RampSettings {
  RampTiming timing;  ///< config `ramp`
  StraightnessLimits straightness;
  bool operator==(const RampSettings&) const = default;
};

/// Reads the config's `ramp` object over `out`'s values; the error names the field
/// ("ramp.hold_s: must be in [1, 60] s") and leaves `out` unchanged.
Status parse_ramp(const nlohmann::json& doc, RampTiming& out);
/// Every field, so that a run.json rebuilds the same ramp whatever the defaults become.
nlohmann::json to_json(const RampTiming& ramp);

}  // namespace stride::opt
