// Simulator command-line options (shared by stride sim and stride-fw --hal sim).
#include "stride/sim_hal/sim_cli.hpp"

#include <cstdio>
#include <optional>
#include <sstream>

#include "stride/sim_hal/physics_engine.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::sim {

void declare_world_options(core::CliArgs& args) {
  for (const WorldOptionInfo& o : world_option_table()) {
    std::string help(o.help);
    if (!o.unit.empty()) help += " [" + std::string(o.unit) + "]";
    std::optional<std::string> default_text;
    if (!o.default_text.empty()) default_text = std::string(o.default_text);
    args.option(world_option_cli_flag(o.key).substr(2), help, true, default_text);
  }
}

Status read_world_spec(const core::CliArgs& args, WorldSpec& out) {
  WorldSpec spec = out;
  for (const WorldOptionInfo& o : world_option_table()) {
    const std::string flag = world_option_cli_flag(o.key);
    for (const std::string& value : args.get_all(flag.substr(2)))
      if (Status s = spec.set(o, value, flag); !s) return s;
  }
  out = std::move(spec);
  return {};
}

Status read_world_options(const core::CliArgs& args, WorldOptions& out) {
  WorldSpec spec;
  if (Status s = read_world_spec(args, spec); !s) return s;
  out = spec.to_options();
  return {};
}

Status read_engine_list(const core::CliArgs& args, const std::string& name,
                        std::vector<EngineKind>& out) {
  std::vector<EngineKind> engines;
  const std::string flag = "--" + name;
  for (const std::string& value : args.get_all(name)) {
    std::stringstream list(value);
    std::string item;
    while (std::getline(list, item, ',')) {
      WorldSpec world;
      if (Status s = world.set("engine", item, flag); !s) return s;
      bool seen = false;
      for (const EngineKind e : engines) seen = seen || e == world.engine;
      if (!seen) engines.push_back(world.engine);
    }
  }
  out = std::move(engines);
  return {};
}

namespace {

/// ", calibrated robot (...)" naming each calibration quantity that differs from the nominal
/// robot in the quantity's words and unit, or "".
std::string describe_calibration(const WorldOptions& o) {
  const WorldFile calibration = calibration_of(o), nominal;
  std::string parts;
  for (const CalibrationQuantity& q : calibration_quantities()) {
    const double value = q.get(calibration);
    if (value == q.get(nominal)) continue;
    char text[96];
    std::snprintf(text, sizeof text, "%s%.*s %.4g%s%.*s", parts.empty() ? "" : "; ",
                  static_cast<int>(q.what.size()), q.what.data(), value, q.unit == "x" ? "" : " ",
                  q.unit == "x" ? 0 : static_cast<int>(q.unit.size()), q.unit.data());
    parts += text;
  }
  return parts.empty() ? "" : ", calibrated robot (" + parts + ")";
}

}  // namespace

std::string describe_world(const WorldOptions& o) {
  const std::string kind = contact_kind_name(o.contact);
  std::string ground = kind == "seed" ? "seed grass" : kind == "turf" ? "turf" : kind + " ground";
  if (o.randomise.contact_range > 0.0) {
    char range[48];
    std::snprintf(range, sizeof range, " (range +-%.3g)", o.randomise.contact_range);
    ground += range;
  }
  return std::string(to_string(o.engine)) + ", " +
         (o.servo.law == ServoLaw::kIdentified ? "identified" : "seed") + " servo law, " +
         to_string(o.imu_kind()) + " IMU, " + ground + ", step " +
         std::to_string(o.physics_step_ns / 1000) + " us" + describe_calibration(o);
}

}  // namespace stride::sim
