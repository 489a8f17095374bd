// World files (world_file.hpp): reading with one-line errors naming the field, writing.
#include "stride/sim_hal/world_file.hpp"

#include "stride/core/json_file.hpp"
#include "stride/sim_hal/world_spec.hpp"

#include <cmath>
#include <initializer_list>
#include <sstream>

namespace stride::sim {

namespace {

using nlohmann::json;

Status unknown_fields(const json& object, const std::string& where,
                      std::initializer_list<const char*> known) {
  for (const auto& item : object.items()) {
    bool ok = false;
    for (const char* k : known) ok = ok || item.key() == k;
    if (!ok) return Status::error(where + item.key() + ": unknown field");
  }
  return Status::ok();
}

std::string range_text(double lo, double hi) {
  std::ostringstream text;
  text << "[" << lo << ", " << hi << "]";
  return text.str();
}

/// A number in [lo, hi] at `object[key]` (kept if absent).
Status read_number(const json& object, const std::string& where, const char* key, double lo,
                   double hi, double& out) {
  if (!object.contains(key)) return Status::ok();
  const json& v = object.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lo ||
      v.get<double>() > hi)
    return Status::error(where + key + ": must be a number in " + range_text(lo, hi) + ", got " +
                         v.dump());
  out = v.get<double>();
  return Status::ok();
}

/// `n` numbers, each within +-limit, at `object[key]` (kept if absent).
template <typename Vector>
Status read_vector(const json& object, const std::string& where, const char* key, double limit,
                   Vector& out) {
  if (!object.contains(key)) return Status::ok();
  const json& v = object.at(key);
  const auto n = static_cast<std::size_t>(out.size());
  bool ok = v.is_array() && v.size() == n;
  for (std::size_t i = 0; ok && i < n; ++i)
    ok = v[i].is_number() && std::abs(v[i].get<double>()) <= limit;
  if (!ok)
    return Status::error(where + key + ": must be " + std::to_string(n) + " numbers, each in " +
                         range_text(-limit, limit) + ", got " + v.dump());
  for (std::size_t i = 0; i < n; ++i) out[static_cast<Eigen::Index>(i)] = v[i].get<double>();
  return Status::ok();
}

Status parse_robot(const json& r, WorldFile& out) {
  const std::string where = "robot.";
  if (!r.is_object()) return Status::error("robot: must be an object");
  if (Status s = unknown_fields(r, where,
                                {"torque_scale", "friction_scale", "latency_ticks",
                                 "trunk_mass_scale", "trunk_com_offset_m"});
      !s)
    return s;
  RobotCalibration& c = out.robot;
  if (r.contains("torque_scale")) {
    const json& t = r.at("torque_scale");
    if (!t.is_object()) return Status::error("robot.torque_scale: must be {\"MX-64\": x, ...}");
    if (Status s = unknown_fields(t, "robot.torque_scale.", {"MX-64", "MX-106"}); !s) return s;
    if (Status s = read_number(t, "robot.torque_scale.", "MX-64", 0.1, 3.0, c.torque_scale_mx64);
        !s)
      return s;
    if (Status s = read_number(t, "robot.torque_scale.", "MX-106", 0.1, 3.0, c.torque_scale_mx106);
        !s)
      return s;
  }
  if (Status s = read_number(r, where, "friction_scale", 0.0, 5.0, c.friction_scale); !s) return s;
  if (Status s = read_number(r, where, "trunk_mass_scale", 0.3, 3.0, c.trunk_mass_scale); !s)
    return s;
  if (Status s = read_vector(r, where, "trunk_com_offset_m", 0.1, c.trunk_com_offset_m); !s)
    return s;
  if (r.contains("latency_ticks")) {
    const json& l = r.at("latency_ticks");
    if (!l.is_number_integer() || l.get<int>() < 0 ||
        l.get<int>() > RobotCalibration::kMaxLatencyTicks)
      return Status::error("robot.latency_ticks: must be an integer in 0.." +
                           std::to_string(RobotCalibration::kMaxLatencyTicks) + ", got " +
                           l.dump());
    c.latency_ticks = l.get<int>();
  }
  return Status::ok();
}

}  // namespace

void WorldFile::apply(WorldOptions& options) const {
  options.apply(base);
  apply_calibration(options);
}

void WorldFile::apply_calibration(WorldOptions& options) const {
  options.battery_voltage_v = supply_voltage_v;
  options.robot = robot;
  options.imu.gyro_bias = gyro_bias_rad_s;
  options.imu.accel_bias = accel_bias_mps2;
}

Status parse_world_file(const json& doc, WorldFile& out) {
  WorldFile w;
  if (!doc.is_object() || doc.value("format", "") != "stride-world")
    return Status::error("not a Stride world file (\"format\" is not \"stride-world\")");
  if (Status s = unknown_fields(
          doc, "",
          {"format", "base", "supply_voltage_v", "robot", "imu", "calibration", "_comment"});
      !s)
    return s;
  if (doc.contains("base")) {
    const json& b = doc.at("base");
    const std::string text = b.is_string() ? b.get<std::string>() : b.dump();
    if (!parse_world_preset(text, w.base))
      return Status::error("base: expected " + world_option_choices(*find_world_option("base")) +
                           ", got '" + text + "'");
  }
  if (Status s = read_number(doc, "", "supply_voltage_v", 9.0, 18.0, w.supply_voltage_v); !s)
    return s;
  if (doc.contains("robot"))
    if (Status s = parse_robot(doc.at("robot"), w); !s) return s;
  if (doc.contains("imu")) {
    const json& i = doc.at("imu");
    if (!i.is_object()) return Status::error("imu: must be an object");
    if (Status s = unknown_fields(i, "imu.", {"gyro_bias_rad_s", "accel_bias_mps2"}); !s) return s;
    if (Status s = read_vector(i, "imu.", "gyro_bias_rad_s", 1.0, w.gyro_bias_rad_s); !s) return s;
    if (Status s = read_vector(i, "imu.", "accel_bias_mps2", 3.0, w.accel_bias_mps2); !s) return s;
  }
  if (doc.contains("calibration")) {
    if (!doc.at("calibration").is_object()) return Status::error("calibration: must be an object");
    w.calibration = doc.at("calibration");
  }
  out = std::move(w);
  return Status::ok();
}

Status load_world_file(const std::filesystem::path& path, WorldFile& out) {
  json doc;
  if (Status s = core::read_json_file(path, doc); !s) return s;
  if (Status s = parse_world_file(doc, out); !s)
    return Status::error(path.string() + ": " + s.message());
  return Status::ok();
}

json to_json(const WorldFile& w) {
  const RobotCalibration& c = w.robot;
  json doc = {
      {"format", "stride-world"},
      {"base", to_string(w.base)},
      {"supply_voltage_v", w.supply_voltage_v},
      {"robot",
       {{"torque_scale", {{"MX-64", c.torque_scale_mx64}, {"MX-106", c.torque_scale_mx106}}},
        {"friction_scale", c.friction_scale},
        {"latency_ticks", c.latency_ticks},
        {"trunk_mass_scale", c.trunk_mass_scale},
        {"trunk_com_offset_m", {c.trunk_com_offset_m.x(), c.trunk_com_offset_m.y()}}}},
      {"imu",
       {{"gyro_bias_rad_s", {w.gyro_bias_rad_s.x(), w.gyro_bias_rad_s.y(), w.gyro_bias_rad_s.z()}},
        {"accel_bias_mps2",
         {w.accel_bias_mps2.x(), w.accel_bias_mps2.y(), w.accel_bias_mps2.z()}}}}};
  if (!w.calibration.empty()) doc["calibration"] = w.calibration;
  return doc;
}

bool looks_like_world_file(const std::string& text) {
  return text.find('/') != std::string::npos ||
         (text.size() > 5 && text.compare(text.size() - 5, 5, ".json") == 0);
}

}  // namespace stride::sim
