// The values stride calibrate fits (calibration.hpp): their names, units, bounds and steps,
// which the routine does not identify (the warnings, from the drawn-robot study of
// tests/bench/RESULTS.md), and reading and setting each in a world file.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "stride/calibration/calibration.hpp"

namespace stride::calibration {

using sim::RobotCalibration;
using sim::WorldFile;

const std::vector<CalibrationParameter>& calibration_parameters() {
  static const std::string kServo =
      "the routine's slow motions let the MX torque scales and the friction trade against each "
      "other and against the model's other differences";
  static const std::string kCom =
      "the routine tells the trunk's centre of mass only when little else differs, and then to "
      "about 2.5 mm";
  static const std::vector<CalibrationParameter> params = {
      {"torque_mx64", "x", "MX-64 torque scale", 0.5, 1.5, 0.1, false,
       "the routine hardly loads the arms and the head, which the MX-64s move"},
      {"torque_mx106", "x", "MX-106 torque scale", 0.5, 1.5, 0.1, false, kServo},
      {"friction", "x", "servo friction scale", 0.2, 3.0, 0.2, false, kServo},
      {"voltage", "V", "supply voltage", 11.0, 16.8, 0.5, false,
       "it trades against the MX-106 torque; the logs measure it (leave it out of --fit)"},
      {"latency", "ticks", "bus latency", 0.0, RobotCalibration::kMaxLatencyTicks, 1.0, true},
      {"trunk_mass", "x", "trunk mass scale", 0.7, 1.5, 0.05, false,
       "it trades against the MX-106 torque and the supply; weigh the robot (--robot-mass)"},
      {"trunk_com_x", "m", "trunk centre of mass, forward", -0.04, 0.04, 0.005, false, kCom},
      {"trunk_com_y", "m", "trunk centre of mass, left", -0.04, 0.04, 0.005, false, kCom},
      {"gyro_bias_x", "rad/s", "gyro bias x", -0.2, 0.2, 0.02},
      {"gyro_bias_y", "rad/s", "gyro bias y", -0.2, 0.2, 0.02},
      {"gyro_bias_z", "rad/s", "gyro bias z", -0.2, 0.2, 0.02},
      {"accel_bias_x", "m/s^2", "accelerometer bias x", -1.0, 1.0, 0.1},
      {"accel_bias_y", "m/s^2", "accelerometer bias y", -1.0, 1.0, 0.1, false, "", "trunk_com_y",
       "the accelerometer's y also reads the trunk's roll, which the trunk's lateral centre of "
       "mass moves through the servos' compliance; fit it without trunk_com_y"},
      {"accel_bias_z", "m/s^2", "accelerometer bias z", -1.0, 1.0, 0.1},
  };
  return params;
}

Status parse_fit_names(const std::string& list, std::vector<std::string>& out) {
  out.clear();
  std::string known;
  for (const CalibrationParameter& p : calibration_parameters())
    known += (known.empty() ? "" : ", ") + p.name;
  std::stringstream in(list);
  std::vector<std::string> wanted;
  for (std::string name; std::getline(in, name, ',');) {
    if (name == "all") {
      for (const CalibrationParameter& p : calibration_parameters()) wanted.push_back(p.name);
    } else if (name == "gyro_bias" || name == "accel_bias") {
      for (const char* axis : {"_x", "_y", "_z"}) wanted.push_back(name + axis);
    } else {
      const auto& params = calibration_parameters();
      if (std::none_of(params.begin(), params.end(),
                       [&name](const CalibrationParameter& p) { return p.name == name; }))
        return Status::error("--fit: cannot fit '" + name + "' (known: " + known +
                             ", gyro_bias, accel_bias, all)");
      wanted.push_back(name);
    }
  }
  if (wanted.empty()) return Status::error("--fit: name at least one parameter (" + known + ")");
  for (const CalibrationParameter& p : calibration_parameters())  // table order, no repeats
    if (std::find(wanted.begin(), wanted.end(), p.name) != wanted.end()) out.push_back(p.name);
  return Status::ok();
}

std::vector<std::string> fit_warnings(const std::vector<std::string>& fit) {
  const auto fitted = [&fit](const std::string& name) {
    return std::find(fit.begin(), fit.end(), name) != fit.end();
  };
  std::vector<std::string> lines;
  for (const CalibrationParameter& p : calibration_parameters()) {
    if (!fitted(p.name)) continue;
    if (!p.caution.empty())
      lines.push_back("--fit " + p.name + ": not identified by the routine (" + p.caution +
                      "); the fitted value is a best guess");
    else if (!p.caution_with.empty() && fitted(p.caution_with))
      lines.push_back("--fit " + p.name + ": not identified by the routine with " + p.caution_with +
                      " also fitted (" + p.caution_with_why +
                      "); the fitted value is a best guess");
  }
  return lines;
}

std::string warning_mark(const CalibrationParameter& p) {
  if (!p.caution.empty()) return "(warned)";
  return p.caution_with.empty() ? "" : "(warned with " + p.caution_with + ")";
}

double calibration_value(const WorldFile& w, const std::string& name) {
  const RobotCalibration& c = w.robot;
  if (name == "torque_mx64") return c.torque_scale_mx64;
  if (name == "torque_mx106") return c.torque_scale_mx106;
  if (name == "friction") return c.friction_scale;
  if (name == "voltage") return w.supply_voltage_v;
  if (name == "latency") return c.latency_ticks;
  if (name == "trunk_mass") return c.trunk_mass_scale;
  if (name == "trunk_com_x") return c.trunk_com_offset_m.x();
  if (name == "trunk_com_y") return c.trunk_com_offset_m.y();
  const int axis = name.back() - 'x';
  if (name.rfind("gyro_bias_", 0) == 0) return w.gyro_bias_rad_s[axis];
  if (name.rfind("accel_bias_", 0) == 0) return w.accel_bias_mps2[axis];
  return std::numeric_limits<double>::quiet_NaN();
}

void set_calibration_value(WorldFile& w, const std::string& name, double v) {
  RobotCalibration& c = w.robot;
  if (name == "torque_mx64") c.torque_scale_mx64 = v;
  if (name == "torque_mx106") c.torque_scale_mx106 = v;
  if (name == "friction") c.friction_scale = v;
  if (name == "voltage") w.supply_voltage_v = v;
  if (name == "latency") c.latency_ticks = static_cast<int>(std::lround(v));
  if (name == "trunk_mass") c.trunk_mass_scale = v;
  if (name == "trunk_com_x") c.trunk_com_offset_m.x() = v;
  if (name == "trunk_com_y") c.trunk_com_offset_m.y() = v;
  const int axis = name.back() - 'x';
  if (name.rfind("gyro_bias_", 0) == 0) w.gyro_bias_rad_s[axis] = v;
  if (name.rfind("accel_bias_", 0) == 0) w.accel_bias_mps2[axis] = v;
}

}  // namespace stride::calibration
