// Simulator command-line options (shared by stride sim and stride-fw --hal sim).
#include "stride/sim_hal/sim_cli.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <sstream>
#include <system_error>

#include "stride/sim_hal/physics_engine.hpp"
#include "stride/sim_hal/world_file.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::sim {

void declare_world_options(core::CliArgs& args) {
  args.option("push",
              "T,DIR,IMPULSE: push the trunk T s after the start, DIR forward|backward|left|right "
              "or degrees anticlockwise from the robot's heading, IMPULSE in N s (a force over "
              "10 ms at the trunk's centre of mass); repeatable",
              true);
  args.option("seed", "world random seed (randomisation and sensor noise)", true, "1");
  args.option("noise", "sensor noise and per-episode IMU bias: on|off", true, "on");
  args.option("urdf", "robot description (URDF) to simulate instead of the igus model", true);
  args.option("world",
              "named world: faithful (identified servo law, CM730 IMU, turf), seed (the "
              "thesis's: seed servo law, ideal IMU, 2 cm grass) or a world file (.json, from "
              "stride calibrate); --servo-law, --imu and --contact override its parts",
              true, "faithful");
  // The rest from the world option table (world_spec.hpp), as the task configs name them.
  for (const WorldOptionInfo& o : world_option_table()) {
    if (o.key == "base") continue;  // --world above: a named world or a world file
    std::string help(o.help);
    if (!o.unit.empty()) help += " [" + std::string(o.unit) + "]";
    args.option(world_option_flag(o.key).substr(2), help, true, std::string(o.default_text));
  }
}

Status read_world_options(const core::CliArgs& args, WorldOptions& out) {
  std::int64_t seed = 1;
  if (Status s = args.get_int("seed", seed); !s) return s;
  if (seed < 0) return Status::error("--seed: must be >= 0, got " + std::to_string(seed));
  out.seed = static_cast<std::uint64_t>(seed);
  const std::string noise = args.get("noise", "on");
  if (noise == "on") {
    out.imu.set_noise(true);
  } else if (noise == "off") {
    out.imu = ImuOptions{};
  } else {
    return Status::error("--noise: expected on or off, got '" + noise + "'");
  }
  if (args.has("urdf")) {
    out.urdf = args.get("urdf");
    std::error_code error;
    if (!std::filesystem::is_regular_file(out.urdf, error))
      return Status::error("--urdf: no such file '" + out.urdf.string() + "'");
    auto model = std::make_shared<RobotModel>();
    if (Status s = RobotModel::load_file(out.urdf, *model); !s)
      return Status::error("--urdf: " + s.message());
    out.model = std::move(model);
  }
  const std::string world = args.get("world", "faithful");
  WorldPreset preset = WorldPreset::kFaithful;
  if (looks_like_world_file(world)) {
    WorldFile file;
    if (Status s = load_world_file(world, file); !s)
      return Status::error("--world: " + s.message());
    file.apply(out);
  } else if (parse_world_preset(world, preset)) {
    out.apply(preset);
  } else {
    return Status::error("--world: expected faithful, seed or a world file (.json), got '" + world +
                         "'");
  }
  // The table's options in its order (after the world, whose parts they override); the step
  // is checked against the firmware's period when the world is built (check_physics_step).
  for (const WorldOptionInfo& o : world_option_table()) {
    if (o.key == "base") continue;
    const std::string flag = world_option_flag(o.key);
    const std::string name = flag.substr(2);
    if (!args.has(name)) continue;
    if (Status s = apply_world_option(o, args.get(name), flag, out); !s) return s;
  }
  // Pushes (repeatable); their times are checked against the episode by its runner.
  for (const std::string& text : args.get_all("push")) {
    TorsoPush push;
    if (Status s = parse_push(text, std::numeric_limits<double>::infinity(), push); !s) return s;
    out.pushes.push_back(push);
  }
  return Status::ok();
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
  const ContactOptions turf = ContactOptions::turf();
  const bool is_turf = o.contact.grass_thickness_m == turf.grass_thickness_m &&
                       o.contact.mujoco_solid_ground == turf.mujoco_solid_ground;
  return std::string(to_string(o.engine)) + ", " +
         (o.servo.law == ServoLaw::kIdentified ? "identified" : "seed") + " servo law, " +
         (o.imu.chain.is_ideal() ? "ideal" : "cm730") + " IMU, " +
         (is_turf ? "turf" : "seed grass") + ", step " + std::to_string(o.physics_step_ns / 1000) +
         " us" + describe_calibration(o);
}

namespace {

bool parse_number(const std::string& text, double& out) {
  try {
    std::size_t used = 0;
    out = std::stod(text, &used);
    return used == text.size() && std::isfinite(out);
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

Status parse_push(const std::string& text, double duration_s, TorsoPush& out) {
  const auto bad = [&text](const std::string& why) {
    return Status::error("--push: " + why + " in '" + text +
                         "' (expected T,DIR,IMPULSE, e.g. 5.2,forward,1.5)");
  };
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) parts.push_back(part);
  if (parts.size() != 3 || text.empty() || text.back() == ',')
    return bad("expected three comma-separated fields");
  if (!parse_number(parts[0], out.time_s)) return bad("bad time '" + parts[0] + "'");
  if (!(out.time_s >= 0.0 && out.time_s < duration_s))
    return bad("time must be in [0, " + std::to_string(duration_s) + ") s (the episode)");
  const std::string& dir = parts[1];
  constexpr double kPi = 3.14159265358979323846;
  if (dir == "forward") {
    out.direction_rad = 0.0;
  } else if (dir == "backward") {
    out.direction_rad = kPi;
  } else if (dir == "left") {
    out.direction_rad = kPi / 2;
  } else if (dir == "right") {
    out.direction_rad = -kPi / 2;
  } else {
    double degrees = 0.0;
    if (!parse_number(dir, degrees))
      return bad("direction must be forward, backward, left, right or degrees, got '" + dir + "'");
    if (!(degrees >= -360.0 && degrees <= 360.0))
      return bad("direction in degrees must be in [-360, 360]");
    out.direction_rad = degrees * kPi / 180.0;
  }
  if (!parse_number(parts[2], out.impulse_n_s)) return bad("bad impulse '" + parts[2] + "'");
  if (!(out.impulse_n_s > 0.0 && out.impulse_n_s <= kMaxPushImpulse))
    return bad("impulse must be in (0, " + std::to_string(static_cast<int>(kMaxPushImpulse)) +
               "] N s");
  return Status::ok();
}

}  // namespace stride::sim
