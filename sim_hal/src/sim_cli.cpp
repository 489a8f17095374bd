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

/// ", calibrated robot (...)" naming what differs from the nominal robot, or "".
std::string describe_calibration(const WorldOptions& o) {
  const RobotCalibration& c = o.robot;
  const RobotCalibration nominal;
  std::string parts;
  const auto add = [&parts](const std::string& name, double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%s%s %.4g", parts.empty() ? "" : ", ", name.c_str(), value);
    parts += text;
  };
  if (o.battery_voltage_v != WorldOptions{}.battery_voltage_v) add("supply V", o.battery_voltage_v);
  if (c.torque_scale_mx64 != nominal.torque_scale_mx64) add("MX-64 torque x", c.torque_scale_mx64);
  if (c.torque_scale_mx106 != nominal.torque_scale_mx106)
    add("MX-106 torque x", c.torque_scale_mx106);
  if (c.friction_scale != nominal.friction_scale) add("friction x", c.friction_scale);
  if (c.latency_ticks != nominal.latency_ticks) add("latency ticks", c.latency_ticks);
  if (c.trunk_mass_scale != nominal.trunk_mass_scale) add("trunk mass x", c.trunk_mass_scale);
  if (c.trunk_com_offset_m.x() != 0.0) add("trunk CoM x +m", c.trunk_com_offset_m.x());
  if (c.trunk_com_offset_m.y() != 0.0) add("trunk CoM y +m", c.trunk_com_offset_m.y());
  if (!o.imu.gyro_bias.isZero()) add("|gyro bias| rad/s", o.imu.gyro_bias.norm());
  if (!o.imu.accel_bias.isZero()) add("|accel bias| m/s^2", o.imu.accel_bias.norm());
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
