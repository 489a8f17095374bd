// What `stride replay` prints and writes from a ReplayResult (stride/sim_hal/log_replay.hpp): the
// text table (per window and overall, then per joint), the --json summary, and the --html page with
// the logged and simulated traces overlaid (inline SVG, no script, no network).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/sim_hal/log_replay.hpp"

namespace stride::calibration {

/// One encoder tick of the MX servos (4096 per revolution) [rad].
inline constexpr double kEncoderTickRad = 2.0 * 3.14159265358979323846 / 4096.0;

/// The errors as JSON: {"position_rms_rad": {"all": x, "per_joint": {name: x, ...}}, ...}.
nlohmann::json to_json(const sim::ReplayErrors& errors,
                       const std::array<std::string, hal::kServoCount>& servo_names);

/// The --json summary: facts (name: value), the windows and the overall errors.
nlohmann::json replay_summary_json(const sim::ReplayResult& result,
                                   const std::vector<std::pair<std::string, std::string>>& facts);

/// The text report: one row per window and the overall row, then the errors per joint.
std::string replay_table(const sim::ReplayResult& result);

/// The --html page (needs ReplayOptions::keep_traces): the facts, the tables, and per joint and
/// IMU channel the logged and simulated traces overlaid, window starts marked.
std::string replay_html(const sim::ReplayResult& result, const std::string& title,
                        const std::vector<std::pair<std::string, std::string>>& facts);

}  // namespace stride::calibration
