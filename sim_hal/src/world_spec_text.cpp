// WorldSpec as text: a `world` JSON object (read and written through the world option table)
// and a push's "T,DIR,IMPULSE" (world_spec.hpp).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "stride/sim_hal/world_spec.hpp"

namespace stride::sim {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A JSON value as the text the table reads: a string as is, a boolean as on/off, else its JSON.
std::string option_text(const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "on" : "off";
  return v.dump();
}

bool parse_number(const std::string& text, double& out) {
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return !text.empty() && *end == '\0' && std::isfinite(out);
}

}  // namespace

Status read_world_spec(const nlohmann::json& object, const std::string& prefix, WorldSpec& out) {
  if (!object.is_object()) return Status::error(prefix + ": must be an object of world options");
  WorldSpec spec = out;  // nothing changes on an error
  for (const auto& [key, value] : object.items()) {
    const std::string shown = prefix + "." + key;
    const WorldOptionInfo* option = find_world_option(key);
    if (option == nullptr)
      return Status::error(shown + ": unknown world option (known: " + world_option_keys() + ")");
    if (option->value == WorldValue::kWorld && value.is_object()) {  // a world file by value
      WorldFile file;
      if (Status s = parse_world_file(value, file); !s)
        return Status::error(shown + ": " + s.message());
      spec.use_world_file(std::move(file));
      continue;
    }
    if (option->value == WorldValue::kPushes) {  // the list replaces what the spec held
      if (!value.is_array())
        return Status::error(shown + ": must be a list of \"T,DIR,IMPULSE\" strings");
      option->clear(spec);
      for (std::size_t i = 0; i < value.size(); ++i) {
        const std::string item = shown + "[" + std::to_string(i) + "]";
        if (!value[i].is_string())
          return Status::error(item + ": must be a \"T,DIR,IMPULSE\" string");
        if (Status s = spec.set(*option, value[i].get<std::string>(), item); !s) return s;
      }
      continue;
    }
    const bool name = option->value == WorldValue::kName || option->value == WorldValue::kWorld;
    if (value.is_object() || value.is_array() || value.is_null())
      return Status::error(shown + ": must be a " + (name ? "name" : "value") + ", got " +
                           value.dump());
    if (Status s = spec.set(*option, option_text(value), shown); !s) return s;
  }
  out = std::move(spec);
  return {};
}

nlohmann::json to_json(const WorldSpec& s) {
  const WorldSpec defaults;
  nlohmann::json j = nlohmann::json::object();
  for (const WorldOptionInfo& o : world_option_table()) {
    nlohmann::json value = o.get(s);
    if (value.is_null() || (!o.always_written && value == o.get(defaults))) continue;
    j[std::string(o.key)] = std::move(value);
  }
  return j;
}

Status parse_push(const std::string& text, double duration_s, TorsoPush& out,
                  const std::string& shown) {
  const auto bad = [&text, &shown](const std::string& why) {
    return Status::error(shown + ": " + why + " in '" + text +
                         "' (expected T,DIR,IMPULSE, e.g. 5.2,forward,1.5)");
  };
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) parts.push_back(part);
  if (parts.size() != 3 || text.empty() || text.back() == ',')
    return bad("expected three comma-separated fields");
  TorsoPush push;
  if (!parse_number(parts[0], push.time_s)) return bad("bad time '" + parts[0] + "'");
  if (!(push.time_s >= 0.0 && push.time_s < duration_s))
    return bad("time must be in [0, " + std::to_string(duration_s) + ") s (the episode)");
  const std::string& dir = parts[1];
  if (dir == "forward") {
    push.direction_rad = 0.0;
  } else if (dir == "backward") {
    push.direction_rad = kPi;
  } else if (dir == "left") {
    push.direction_rad = kPi / 2;
  } else if (dir == "right") {
    push.direction_rad = -kPi / 2;
  } else {
    double degrees = 0.0;
    if (!parse_number(dir, degrees))
      return bad("direction must be forward, backward, left, right or degrees, got '" + dir + "'");
    if (!(degrees >= -360.0 && degrees <= 360.0))
      return bad("direction in degrees must be in [-360, 360]");
    push.direction_rad = degrees * kPi / 180.0;
  }
  if (!parse_number(parts[2], push.impulse_n_s)) return bad("bad impulse '" + parts[2] + "'");
  if (!(push.impulse_n_s > 0.0 && push.impulse_n_s <= kMaxPushImpulse))
    return bad("impulse must be in (0, " + std::to_string(static_cast<int>(kMaxPushImpulse)) +
               "] N s");
  out = push;
  return Status::ok();
}

std::string push_text(const TorsoPush& p) {
  const auto exact = [](double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", v);
    return std::string(text);
  };
  std::string direction = exact(p.direction_rad * 180.0 / kPi);
  if (p.direction_rad == 0.0) direction = "forward";
  if (p.direction_rad == kPi) direction = "backward";
  if (p.direction_rad == kPi / 2) direction = "left";
  if (p.direction_rad == -kPi / 2) direction = "right";
  return exact(p.time_s) + "," + direction + "," + exact(p.impulse_n_s);
}

}  // namespace stride::sim
