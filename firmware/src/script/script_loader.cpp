// Script JSON loading and validation (format: firmware/scripts/README.md).
#include <algorithm>
#include <cmath>
#include <set>

#include <nlohmann/json.hpp>

#include "stride/firmware/parameter_store.hpp"  // format_number
#include "stride/firmware/script/script.hpp"

#include "stride/core/json_file.hpp"

#ifndef STRIDE_FIRMWARE_DATA_DIR
#define STRIDE_FIRMWARE_DATA_DIR "."
#endif

namespace stride::fw {

int Script::total_duration_ms() const {
  int total = 0;
  for (const ScriptFrame& frame : frames) total += frame.duration_ms;
  return total;
}

double torque_limit_from_percent(double torque) {
  return std::clamp(torque, 0.0, 100.0) / 100.0;
}

std::filesystem::path default_script_folder() {
  return std::filesystem::path(STRIDE_FIRMWARE_DATA_DIR) / "scripts";
}

namespace {

Status fail(const std::string& where, const std::string& what) {
  return Status::error(where + ": " + what);
}

bool valid_script_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

Status check_keys(const nlohmann::json& object, const std::string& where,
                  std::initializer_list<const char*> allowed) {
  for (const auto& item : object.items()) {
    const bool known = std::any_of(allowed.begin(), allowed.end(),
                                   [&](const char* key) { return item.key() == key; });
    if (!known && item.key().rfind("_comment", 0) != 0) {
      return fail(where + "." + item.key(), "unknown field");
    }
  }
  return {};
}

Status read_number(const nlohmann::json& object, const std::string& where, const char* key,
                   double& out) {
  if (!object.contains(key)) return fail(where + "." + key, "missing");
  const auto& v = object[key];
  if (!v.is_number()) return fail(where + "." + key, "must be a number, got " + v.dump());
  out = v.get<double>();
  if (!std::isfinite(out)) return fail(where + "." + key, "must be finite");
  return {};
}

Status read_percent(const nlohmann::json& object, const std::string& where, const char* key,
                    double& out) {
  if (Status s = read_number(object, where, key, out); !s) return s;
  if (out < 0.0 || out > 100.0) {
    return fail(where + "." + key, format_number(out) + " outside [0, 100]");
  }
  return {};
}

Status parse_target(const nlohmann::json& doc, const std::string& where, const ServoTable& servos,
                    ScriptTarget& out) {
  if (!doc.is_object()) return fail(where, "must be an object");
  if (Status s = check_keys(doc, where, {"servo", "position", "gain", "torque"}); !s) return s;
  if (!doc.contains("servo")) return fail(where + ".servo", "missing");
  if (!doc["servo"].is_string()) {
    return fail(where + ".servo", "must be a servo name, got " + doc["servo"].dump());
  }
  const std::string servo_name = doc["servo"].get<std::string>();
  const auto index = servos.index_of(servo_name);
  if (!index) return fail(where + ".servo", "unknown servo '" + servo_name + "'");
  out.servo = *index;
  const ServoSpec& spec = servos[*index];
  if (Status s = read_number(doc, where, "position", out.position_rad); !s) return s;
  if (out.position_rad < spec.min_rad || out.position_rad > spec.max_rad) {
    return fail(where + ".position", format_number(out.position_rad) + " outside the " + spec.name +
                                         " limits [" + format_number(spec.min_rad) + ", " +
                                         format_number(spec.max_rad) + "] rad");
  }
  if (Status s = read_percent(doc, where, "gain", out.gain); !s) return s;
  if (Status s = read_percent(doc, where, "torque", out.torque); !s) return s;
  return {};
}

/// "pitch_min" < "pitch_max", each within +-pi/2 [rad].
Status read_pitch_band(const nlohmann::json& doc, const std::string& where, double& min,
                       double& max) {
  constexpr double kHalfPi = 1.5707963267948966;
  if (Status s = read_number(doc, where, "pitch_min", min); !s) return s;
  if (Status s = read_number(doc, where, "pitch_max", max); !s) return s;
  for (const auto& [key, v] : {std::pair{"pitch_min", min}, std::pair{"pitch_max", max}})
    if (v < -kHalfPi || v > kHalfPi)
      return fail(where + "." + key, format_number(v) + " outside [-pi/2, pi/2] rad");
  if (!(min < max))
    return fail(where, "pitch_min " + format_number(min) + " must be below pitch_max " +
                           format_number(max));
  return {};
}

Status parse_wait(const nlohmann::json& doc, const std::string& where, ScriptWait& out) {
  if (!doc.is_object()) return fail(where, "must be an object");
  if (Status s = check_keys(doc, where, {"pitch_min", "pitch_max", "rate_max", "timeout_ms"}); !s)
    return s;
  ScriptWait w;
  w.enabled = true;
  if (Status s = read_pitch_band(doc, where, w.pitch_min_rad, w.pitch_max_rad); !s) return s;
  if (doc.contains("rate_max")) {
    if (Status s = read_number(doc, where, "rate_max", w.rate_max_rad_s); !s) return s;
    if (w.rate_max_rad_s < 0.0 || w.rate_max_rad_s > 20.0)
      return fail(where + ".rate_max", format_number(w.rate_max_rad_s) + " outside [0, 20] rad/s");
  }
  double timeout = 0.0;
  if (Status s = read_number(doc, where, "timeout_ms", timeout); !s) return s;
  if (timeout != std::floor(timeout) || timeout < 0 || timeout > kMaxFrameDurationMs)
    return fail(where + ".timeout_ms", "must be an integer 0.." +
                                           std::to_string(kMaxFrameDurationMs) + ", got " +
                                           format_number(timeout));
  w.timeout_ms = static_cast<int>(timeout);
  out = w;
  return {};
}

Status parse_guard(const nlohmann::json& doc, const std::string& where, ScriptGuard& out) {
  if (!doc.is_object()) return fail(where, "must be an object");
  if (Status s = check_keys(doc, where, {"pitch_min", "pitch_max"}); !s) return s;
  ScriptGuard g;
  g.enabled = true;
  if (Status s = read_pitch_band(doc, where, g.pitch_min_rad, g.pitch_max_rad); !s) return s;
  out = g;
  return {};
}

Status parse_frame(const nlohmann::json& doc, const std::string& where, const ServoTable& servos,
                   ScriptFrame& out) {
  if (!doc.is_object()) return fail(where, "must be an object");
  if (Status s = check_keys(doc, where, {"duration_ms", "targets", "wait", "guard"}); !s) return s;
  out.wait = ScriptWait{};
  out.guard = ScriptGuard{};
  if (doc.contains("wait"))
    if (Status s = parse_wait(doc["wait"], where + ".wait", out.wait); !s) return s;
  if (doc.contains("guard"))
    if (Status s = parse_guard(doc["guard"], where + ".guard", out.guard); !s) return s;
  double duration = 0.0;
  if (Status s = read_number(doc, where, "duration_ms", duration); !s) return s;
  if (duration != std::floor(duration) || duration < 1 || duration > kMaxFrameDurationMs) {
    return fail(where + ".duration_ms", "must be an integer 1.." +
                                            std::to_string(kMaxFrameDurationMs) + ", got " +
                                            format_number(duration));
  }
  out.duration_ms = static_cast<int>(duration);
  if (!doc.contains("targets") || !doc["targets"].is_array() || doc["targets"].empty()) {
    return fail(where + ".targets", "missing or not a non-empty array");
  }
  const auto& targets = doc["targets"];
  std::set<std::size_t> seen;
  out.targets.clear();
  out.targets.reserve(targets.size());
  for (std::size_t j = 0; j < targets.size(); ++j) {
    const std::string target_where = where + ".targets[" + std::to_string(j) + "]";
    ScriptTarget target;
    if (Status s = parse_target(targets[j], target_where, servos, target); !s) return s;
    if (!seen.insert(target.servo).second) {
      return fail(target_where + ".servo",
                  "servo '" + servos[target.servo].name + "' listed twice in this frame");
    }
    out.targets.push_back(target);
  }
  return {};
}

}  // namespace

Status parse_script(const nlohmann::json& doc, std::string_view origin, const ServoTable& servos,
                    Script& out) {
  const std::string file(origin);
  if (!doc.is_object()) return fail(file, "must be a JSON object");
  if (Status s = check_keys(doc, file, {"name", "description", "frames"}); !s) return s;
  Script script;
  if (!doc.contains("name") || !doc["name"].is_string()) {
    return fail(file + ": name", "missing or not a string");
  }
  script.name = doc["name"].get<std::string>();
  if (!valid_script_name(script.name)) {
    return fail(file + ": name", "'" + script.name + "' must match [a-z0-9_]+ (at most 64)");
  }
  if (doc.contains("description")) {
    if (!doc["description"].is_string()) return fail(file + ": description", "must be a string");
    script.description = doc["description"].get<std::string>();
  }
  if (!doc.contains("frames") || !doc["frames"].is_array() || doc["frames"].empty()) {
    return fail(file + ": frames", "missing or not a non-empty array");
  }
  const auto& frames = doc["frames"];
  if (frames.size() > kMaxScriptFrames) {
    return fail(file + ": frames", "at most " + std::to_string(kMaxScriptFrames) + " frames, got " +
                                       std::to_string(frames.size()));
  }
  script.frames.resize(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const std::string where = file + ": frames[" + std::to_string(i) + "]";
    if (Status s = parse_frame(frames[i], where, servos, script.frames[i]); !s) return s;
  }
  out = std::move(script);
  return {};
}

Status load_script_file(const std::filesystem::path& path, const ServoTable& servos, Script& out) {
  const std::string file = path.string();
  nlohmann::json doc;
  if (Status s = core::read_json_file(path, doc); !s) return s;
  return parse_script(doc, file, servos, out);
}

Status load_script_folder(const std::filesystem::path& folder, const ServoTable& servos,
                          std::vector<Script>& out) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) {
    return Status::error(folder.string() + ": not a folder");
  }
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".json") {
      files.push_back(entry.path());
    }
  }
  if (ec) return Status::error(folder.string() + ": cannot list (" + ec.message() + ")");
  std::sort(files.begin(), files.end());
  std::vector<Script> scripts;
  std::set<std::string> names;
  for (const auto& file : files) {
    Script script;
    if (Status s = load_script_file(file, servos, script); !s) return s;
    if (!names.insert(script.name).second) {
      return Status::error(file.string() + ": name: script '" + script.name +
                           "' already defined by another file");
    }
    scripts.push_back(std::move(script));
  }
  out = std::move(scripts);
  return {};
}

nlohmann::json script_to_json(const Script& script, const ServoTable& servos) {
  nlohmann::json doc;
  doc["name"] = script.name;
  if (!script.description.empty()) doc["description"] = script.description;
  nlohmann::json frames = nlohmann::json::array();
  for (const ScriptFrame& frame : script.frames) {
    nlohmann::json targets = nlohmann::json::array();
    for (const ScriptTarget& t : frame.targets) {
      targets.push_back({{"servo", servos[t.servo].name},
                         {"position", t.position_rad},
                         {"gain", t.gain},
                         {"torque", t.torque}});
    }
    nlohmann::json f = {{"duration_ms", frame.duration_ms}, {"targets", std::move(targets)}};
    if (frame.wait.enabled)
      f["wait"] = {{"pitch_min", frame.wait.pitch_min_rad},
                   {"pitch_max", frame.wait.pitch_max_rad},
                   {"rate_max", frame.wait.rate_max_rad_s},
                   {"timeout_ms", frame.wait.timeout_ms}};
    if (frame.guard.enabled)
      f["guard"] = {{"pitch_min", frame.guard.pitch_min_rad},
                    {"pitch_max", frame.guard.pitch_max_rad}};
    frames.push_back(std::move(f));
  }
  doc["frames"] = std::move(frames);
  return doc;
}

}  // namespace stride::fw
