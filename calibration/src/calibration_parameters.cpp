// The values stride calibrate fits (calibration.hpp): their search bounds and steps, which the
// routine does not identify (the warnings, from the drawn-robot study of tests/bench/RESULTS.md),
// and reading and setting each in a world file. Their names, units, words and ranges are the
// world file's calibration quantities (sim::calibration_quantities, world_file.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "stride/calibration/calibration.hpp"

namespace stride::calibration {

using sim::RobotCalibration;
using sim::WorldFile;

namespace {

/// How stride calibrate fits one calibration quantity (its name, unit, words and range are
/// sim::calibration_quantities()'s): the search bounds, inside the quantity's range (a test
/// holds), the first step and the warnings.
struct FitBounds {
  std::string_view name;
  double lower = 0.0, upper = 0.0, step = 0.0;
  std::string caution = {}, caution_with = {}, caution_with_why = {};
};

const std::vector<FitBounds>& fit_bounds() {
  static const std::string kServo =
      "the routine's slow motions let the MX torque scales and the friction trade against each "
      "other and against the model's other differences";
  static const std::string kArms =
      "with identify_arms in the logs the staged fit lands it within 20 % on 13 of 20 drawn "
      "robots, short of 16: on the arms the MX-64 torque and the friction still trade";
  static const std::string kCom =
      "the routine tells the trunk's centre of mass only when little else differs, and then to "
      "about 2.5 mm";
  static const std::vector<FitBounds> bounds = {
      {"torque_mx64", 0.5, 1.5, 0.1, kArms},
      {"torque_mx106", 0.5, 1.5, 0.1, kServo},
      {"friction", 0.2, 3.0, 0.2, kArms},
      {"voltage", 11.0, 16.8, 0.5,
       "it trades against the MX-106 torque; the logs measure it (leave it out of --fit)"},
      {"latency", 0.0, RobotCalibration::kMaxLatencyTicks, 1.0},
      {"trunk_mass", 0.7, 1.5, 0.05,
       "it trades against the MX-106 torque and the supply; weigh the robot (--robot-mass)"},
      {"trunk_com_x", -0.04, 0.04, 0.005, kCom},
      {"trunk_com_y", -0.04, 0.04, 0.005, kCom},
      {"gyro_bias_x", -0.2, 0.2, 0.02},
      {"gyro_bias_y", -0.2, 0.2, 0.02},
      {"gyro_bias_z", -0.2, 0.2, 0.02},
      {"accel_bias_x", -1.0, 1.0, 0.1},
      {"accel_bias_y", -1.0, 1.0, 0.1, "", "trunk_com_y",
       "the accelerometer's y also reads the trunk's roll, which the trunk's lateral centre of "
       "mass moves through the servos' compliance; fit it without trunk_com_y"},
      {"accel_bias_z", -1.0, 1.0, 0.1},
  };
  return bounds;
}

}  // namespace

const std::vector<CalibrationParameter>& calibration_parameters() {
  // In the quantities' order; a quantity without fit bounds is not fitted.
  static const std::vector<CalibrationParameter> params = [] {
    std::vector<CalibrationParameter> out;
    for (const sim::CalibrationQuantity& q : sim::calibration_quantities())
      for (const FitBounds& f : fit_bounds())
        if (f.name == q.name)
          out.push_back({std::string(q.name), std::string(q.unit), std::string(q.what), f.lower,
                         f.upper, f.step, q.whole, f.caution, f.caution_with, f.caution_with_why});
    return out;
  }();
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
  const sim::CalibrationQuantity* q = sim::find_calibration_quantity(name);
  return q != nullptr ? q->get(w) : std::numeric_limits<double>::quiet_NaN();
}

void set_calibration_value(WorldFile& w, const std::string& name, double v) {
  if (const sim::CalibrationQuantity* q = sim::find_calibration_quantity(name); q != nullptr)
    q->set(w, v);
}

}  // namespace stride::calibration
