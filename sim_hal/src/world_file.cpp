// World files (world_file.hpp): reading with one-line errors naming the field, writing.
#include "stride/sim_hal/world_file.hpp"

#include "stride/core/json_file.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/sim_hal/world_spec.hpp"

#include <cmath>
#include <initializer_list>
#include <sstream>

namespace stride::sim {

namespace {

using nlohmann::json;

template <int axis>
double com(const WorldFile& w) {
  return w.robot.trunk_com_offset_m[axis];
}
template <int axis>
void set_com(WorldFile& w, double v) {
  w.robot.trunk_com_offset_m[axis] = v;
}
template <int axis>
double gyro(const WorldFile& w) {
  return w.gyro_bias_rad_s[axis];
}
template <int axis>
void set_gyro(WorldFile& w, double v) {
  w.gyro_bias_rad_s[axis] = v;
}
template <int axis>
double accel(const WorldFile& w) {
  return w.accel_bias_mps2[axis];
}
template <int axis>
void set_accel(WorldFile& w, double v) {
  w.accel_bias_mps2[axis] = v;
}

/// The ranges a robot may differ from the model by, in the units of the file: a servo's
/// torque 0.1 to 3 times the datasheet's, its friction up to 5 times, the supply of a 4S
/// battery and then some, the trunk 0.3 to 3 times its mass and its centre of mass within
/// 10 cm, a gyro bias up to 1 rad/s and an accelerometer bias up to 3 m/s^2 per axis.
const std::vector<CalibrationQuantity>& quantities() {
  static const std::vector<CalibrationQuantity> table = {
      {"torque_mx64", "robot.torque_scale.MX-64", "x", "MX-64 torque scale", 0.1, 3.0, false,
       [](const WorldFile& w) { return w.robot.torque_scale_mx64; },
       [](WorldFile& w, double v) { w.robot.torque_scale_mx64 = v; }},
      {"torque_mx106", "robot.torque_scale.MX-106", "x", "MX-106 torque scale", 0.1, 3.0, false,
       [](const WorldFile& w) { return w.robot.torque_scale_mx106; },
       [](WorldFile& w, double v) { w.robot.torque_scale_mx106 = v; }},
      {"friction", "robot.friction_scale", "x", "servo friction scale", 0.0, 5.0, false,
       [](const WorldFile& w) { return w.robot.friction_scale; },
       [](WorldFile& w, double v) { w.robot.friction_scale = v; }},
      {"voltage", "supply_voltage_v", "V", "supply voltage", 9.0, 18.0, false,
       [](const WorldFile& w) { return w.supply_voltage_v; },
       [](WorldFile& w, double v) { w.supply_voltage_v = v; }},
      {"latency", "robot.latency_ticks", "ticks", "bus latency", 0.0,
       static_cast<double>(RobotCalibration::kMaxLatencyTicks), true,
       [](const WorldFile& w) { return static_cast<double>(w.robot.latency_ticks); },
       [](WorldFile& w, double v) { w.robot.latency_ticks = static_cast<int>(std::lround(v)); }},
      {"trunk_mass", "robot.trunk_mass_scale", "x", "trunk mass scale", 0.3, 3.0, false,
       [](const WorldFile& w) { return w.robot.trunk_mass_scale; },
       [](WorldFile& w, double v) { w.robot.trunk_mass_scale = v; }},
      {"trunk_com_x", "robot.trunk_com_offset_m[0]", "m", "trunk centre of mass, forward", -0.1,
       0.1, false, com<0>, set_com<0>},
      {"trunk_com_y", "robot.trunk_com_offset_m[1]", "m", "trunk centre of mass, left", -0.1, 0.1,
       false, com<1>, set_com<1>},
      {"gyro_bias_x", "imu.gyro_bias_rad_s[0]", "rad/s", "gyro bias x", -1.0, 1.0, false, gyro<0>,
       set_gyro<0>},
      {"gyro_bias_y", "imu.gyro_bias_rad_s[1]", "rad/s", "gyro bias y", -1.0, 1.0, false, gyro<1>,
       set_gyro<1>},
      {"gyro_bias_z", "imu.gyro_bias_rad_s[2]", "rad/s", "gyro bias z", -1.0, 1.0, false, gyro<2>,
       set_gyro<2>},
      {"accel_bias_x", "imu.accel_bias_mps2[0]", "m/s^2", "accelerometer bias x", -3.0, 3.0, false,
       accel<0>, set_accel<0>},
      {"accel_bias_y", "imu.accel_bias_mps2[1]", "m/s^2", "accelerometer bias y", -3.0, 3.0, false,
       accel<1>, set_accel<1>},
      {"accel_bias_z", "imu.accel_bias_mps2[2]", "m/s^2", "accelerometer bias z", -3.0, 3.0, false,
       accel<2>, set_accel<2>},
  };
  return table;
}

const CalibrationQuantity& quantity(std::string_view name) {
  return *find_calibration_quantity(name);
}

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

/// A number in the range of quantity `name` at `object[key]` (kept if absent).
Status read_number(const json& object, const std::string& where, const char* key,
                   std::string_view name, double& out) {
  if (!object.contains(key)) return Status::ok();
  const double lo = quantity(name).min, hi = quantity(name).max;
  const json& v = object.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lo ||
      v.get<double>() > hi)
    return Status::error(where + key + ": must be a number in " + range_text(lo, hi) + ", got " +
                         v.dump());
  out = v.get<double>();
  return Status::ok();
}

/// `n` numbers, each within +-limit, at `object[key]` (kept if absent); the limit is that of
/// the quantity `axis_x` (its axes share the range, a test holds).
template <typename Vector>
Status read_vector(const json& object, const std::string& where, const char* key,
                   std::string_view axis_x, Vector& out) {
  if (!object.contains(key)) return Status::ok();
  const double limit = quantity(axis_x).max;
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
    if (Status s =
            read_number(t, "robot.torque_scale.", "MX-64", "torque_mx64", c.torque_scale_mx64);
        !s)
      return s;
    if (Status s =
            read_number(t, "robot.torque_scale.", "MX-106", "torque_mx106", c.torque_scale_mx106);
        !s)
      return s;
  }
  if (Status s = read_number(r, where, "friction_scale", "friction", c.friction_scale); !s)
    return s;
  if (Status s = read_number(r, where, "trunk_mass_scale", "trunk_mass", c.trunk_mass_scale); !s)
    return s;
  if (Status s = read_vector(r, where, "trunk_com_offset_m", "trunk_com_x", c.trunk_com_offset_m);
      !s)
    return s;
  if (r.contains("latency_ticks")) {
    const json& l = r.at("latency_ticks");
    const CalibrationQuantity& q = quantity("latency");
    if (!l.is_number_integer() || l.get<double>() < q.min || l.get<double>() > q.max)
      return Status::error("robot.latency_ticks: must be an integer in " +
                           fw::format_number(q.min) + ".." + fw::format_number(q.max) + ", got " +
                           l.dump());
    c.latency_ticks = l.get<int>();
  }
  return Status::ok();
}

}  // namespace

const std::vector<CalibrationQuantity>& calibration_quantities() {
  return quantities();
}

const CalibrationQuantity* find_calibration_quantity(std::string_view name) {
  for (const CalibrationQuantity& q : quantities())
    if (q.name == name) return &q;
  return nullptr;
}

WorldFile calibration_of(const WorldOptions& options) {
  WorldFile w;
  w.supply_voltage_v = options.battery_voltage_v;
  w.robot = options.robot;
  w.gyro_bias_rad_s = options.imu.gyro_bias;
  w.accel_bias_mps2 = options.imu.accel_bias;
  return w;
}

Status check_calibration(const WorldFile& world) {
  for (const CalibrationQuantity& q : quantities()) {
    const double v = q.get(world);
    if (!(v >= q.min && v <= q.max))
      return Status::error("robot calibration: " + std::string(q.what) + " must be in " +
                           fw::format_number(q.min) + ".." + fw::format_number(q.max) +
                           (q.unit == "x" ? "" : " " + std::string(q.unit)) + ", got " +
                           fw::format_number(v));
  }
  return Status::ok();
}

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
  if (Status s = read_number(doc, "", "supply_voltage_v", "voltage", w.supply_voltage_v); !s)
    return s;
  if (doc.contains("robot"))
    if (Status s = parse_robot(doc.at("robot"), w); !s) return s;
  if (doc.contains("imu")) {
    const json& i = doc.at("imu");
    if (!i.is_object()) return Status::error("imu: must be an object");
    if (Status s = unknown_fields(i, "imu.", {"gyro_bias_rad_s", "accel_bias_mps2"}); !s) return s;
    if (Status s = read_vector(i, "imu.", "gyro_bias_rad_s", "gyro_bias_x", w.gyro_bias_rad_s); !s)
      return s;
    if (Status s = read_vector(i, "imu.", "accel_bias_mps2", "accel_bias_x", w.accel_bias_mps2); !s)
      return s;
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
