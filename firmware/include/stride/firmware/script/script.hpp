// Keyframe scripts: the data of one script (frames of timed servo targets) and its JSON loader.
//
// A script is a list of frames. Each frame lasts `duration_ms` milliseconds and lists the
// servos it moves: for each, the target position (URDF joint angle [rad]), the gain g (0-100,
// mapped to the MX P register by gain_to_p_register in stand_pose.hpp) and the torque (0-100 % of
// the servo's maximum, 0 = limp). Servos a frame does not list keep moving towards their next
// listed target. This is the NUbots/igus script model (igus.md section 3) with URDF angles; the
// file format is documented in firmware/scripts/README.md.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "stride/core/status.hpp"
#include "stride/firmware/servo_table.hpp"

namespace stride::fw {

/// One servo target of a frame.
struct ScriptTarget {
  std::size_t servo = 0;      ///< servo index 0..19 (Dynamixel ID - 1)
  double position_rad = 0.0;  ///< goal, URDF joint angle [rad], inside the servo table limits
  double gain = 0.0;          ///< 0..100 (P register = round(2.54 g), capped at 254)
  double torque = 100.0;      ///< 0..100 % of maximum torque; 0 switches the servo off
};

/// A frame's end on what the IMU says (issue 54, a get-up that closes the loop): at the frame's
/// deadline the script holds the frame's targets until the trunk's pitch (the firmware's
/// attitude estimate: 0 upright, + nose down, -pi/2 lying on the back) is within
/// [pitch_min, pitch_max] and its rate |gyro y| at most rate_max; the later frames move back by
/// the time waited. Not there within timeout_ms: the script aborts (ScriptEngine::aborted).
struct ScriptWait {
  bool enabled = false;
  double pitch_min_rad = -1.5707963267948966;
  double pitch_max_rad = 1.5707963267948966;
  double rate_max_rad_s = 20.0;  ///< 0..20
  int timeout_ms = 1000;         ///< 0..60000
};

/// A band the trunk's pitch must stay in while the frame plays (from its start to its end,
/// waiting included): outside it the script aborts, so that a rise going wrong ends in the
/// motion manager's soft hold instead of being thrown through.
struct ScriptGuard {
  bool enabled = false;
  double pitch_min_rad = -1.5707963267948966;
  double pitch_max_rad = 1.5707963267948966;
};

/// One keyframe: targets to reach `duration_ms` after the previous frame's deadline.
struct ScriptFrame {
  int duration_ms = 0;                ///< 1..60000
  std::vector<ScriptTarget> targets;  ///< in file order, each servo at most once
  ScriptWait wait;                    ///< optional ("wait" in the file)
  ScriptGuard guard;                  ///< optional ("guard" in the file)
};

struct Script {
  std::string name;                 ///< [a-z0-9_]+, e.g. "kick_right" (also the parameter prefix)
  std::string description;          ///< free text from the file ("" if absent)
  std::vector<ScriptFrame> frames;  ///< at least one

  /// Sum of the frame durations [ms] (before any duration modifier).
  int total_duration_ms() const;
};

/// Limits the loader enforces.
inline constexpr int kMaxFrameDurationMs = 60'000;
inline constexpr std::size_t kMaxScriptFrames = 64;

/// Torque limit fraction [0, 1] for a script torque in [0, 100] %.
double torque_limit_from_percent(double torque);

/// Parses and validates a script document. `origin` (normally the file name) starts every
/// error message, which then names the frame and the field, e.g.
///   "kick_right.json: frames[2].targets[4].position: 3.5 outside the r_knee limits [-0.05, 2.6]".
/// Checks: an object with "name" (matching [a-z0-9_]+) and a non-empty "frames" array of at most
/// kMaxScriptFrames; each frame an object with an integer "duration_ms" in 1..60000 and a
/// non-empty "targets" array; each target an object with "servo" (a servo table name, at most
/// once per frame), "position" (finite, within the servo's limits), "gain" and "torque"
/// (0..100); an optional "wait" {"pitch_min", "pitch_max" (rad, -pi/2..pi/2, min < max),
/// "rate_max" (rad/s, 0..20, optional), "timeout_ms" (0..60000)} and "guard" {"pitch_min",
/// "pitch_max"}; no unknown keys anywhere (a misspelt key is an error, not a silent default).
Status parse_script(const nlohmann::json& doc, std::string_view origin, const ServoTable& servos,
                    Script& out);

/// Reads and parses a script file (see parse_script); errors start with the file path.
Status load_script_file(const std::filesystem::path& path, const ServoTable& servos, Script& out);

/// Loads every *.json file of a folder, in file-name order; fails on the first bad file or on
/// two scripts with the same name.
Status load_script_folder(const std::filesystem::path& folder, const ServoTable& servos,
                          std::vector<Script>& out);

/// The stock scripts' folder (firmware/scripts in the source tree).
std::filesystem::path default_script_folder();

/// The script as a JSON document in the file format (round-trips through parse_script).
nlohmann::json script_to_json(const Script& script, const ServoTable& servos);

}  // namespace stride::fw
