// The straightness limits of the walking tasks (walk, walk-omni, walk-ramp): one part that each
// of those task types' own settings holds (WalkSettings, OmniSettings, RampSettings), parsed and
// written by those types only (config fields `max_drift_ratio`, `max_heading_change_deg`,
// `max_turn_translation_m`; a negative value switches a limit off, written as null in JSON).
// Lateral drift at most max_drift_ratio of the distance walked, heading change at most
// max_heading_change_deg; walk-omni's and walk-ramp's turns translate at most
// max_turn_translation_m (the walk has no turn and does not read it).
#pragma once

#include <string_view>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"

namespace stride::opt {

struct StraightnessLimits {
  double max_drift_ratio = 0.1;
  double max_heading_change_deg = 10.0;
  double max_turn_translation_m = 0.1;
  bool operator==(const StraightnessLimits&) const = default;
};

/// The config fields of the limits (a task type's settings_fields()).
inline constexpr std::string_view kStraightnessFields[] = {
    "max_drift_ratio", "max_heading_change_deg", "max_turn_translation_m"};

/// Reads the limits from the config's fields over `out`'s values: a number >= 0, or null (off);
/// the error names the field.
Status parse_straightness(const nlohmann::json& doc, StraightnessLimits& out);
/// Writes the limits as the config's fields into `doc` (off: null).
void write_straightness(const StraightnessLimits& limits, nlohmann::json& doc);

}  // namespace stride::opt
