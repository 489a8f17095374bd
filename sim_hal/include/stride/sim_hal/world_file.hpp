// A world file: a named world (WorldPreset) and how one robot differs from the model
// (RobotCalibration, the supply voltage, the IMU's fixed biases). `stride calibrate` writes one
// from the robot's flight logs; `--world FILE` (stride sim, stride-fw --hal sim, stride vbus
// --sim, stride replay, stride validate via the run's config) and a task config's "world" read
// it. Format (JSON, every field but "format" optional, nominal when absent):
//
//   {"format": "stride-world", "base": "faithful" | "seed",
//    "supply_voltage_v": 14.8,
//    "robot": {"torque_scale": {"MX-64": 1, "MX-106": 1}, "friction_scale": 1,
//              "latency_ticks": 0, "trunk_mass_scale": 1, "trunk_com_offset_m": [0, 0]},
//    "imu": {"gyro_bias_rad_s": [0, 0, 0], "accel_bias_mps2": [0, 0, 0]},
//    "calibration": {...}}   // stride calibrate's record: logs, fitted values, uncertainties
//
// Unknown fields and out-of-range values are errors naming the field. Each calibrated value
// has one name, unit, range and description, in calibration_quantities(): the world file reads
// it in that range, SimWorld refuses a world outside it, `stride calibrate --fit` fits it
// within bounds inside it and describe_world names it with its words.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::sim {

struct WorldFile {
  WorldPreset base = WorldPreset::kFaithful;
  double supply_voltage_v =
      kNominalSupplyVoltage;  ///< the robot's battery (WorldOptions::battery_voltage_v)
  RobotCalibration robot;
  Eigen::Vector3d gyro_bias_rad_s = Eigen::Vector3d::Zero();  ///< fixed IMU biases, torso frame
  Eigen::Vector3d accel_bias_mps2 = Eigen::Vector3d::Zero();
  nlohmann::json calibration = nlohmann::json::object();  ///< provenance (not interpreted)

  /// Sets the base world's servo law, IMU chain and contact, then the calibration.
  void apply(WorldOptions& options) const;
  /// Sets the calibration alone (the voltage, RobotCalibration, the IMU's fixed biases).
  void apply_calibration(WorldOptions& options) const;
};

/// One calibrated value of a world file (issue 44 point 2): its one name (`stride calibrate
/// --fit NAME`), where the file holds it, unit, words, range and field.
struct CalibrationQuantity {
  std::string_view name;        ///< "torque_mx106"
  std::string_view field;       ///< in the world file: "robot.torque_scale.MX-106"
  std::string_view unit;        ///< "x" for a scale
  std::string_view what;        ///< "MX-106 torque scale"
  double min = 0.0, max = 0.0;  ///< the range (inclusive)
  bool whole = false;           ///< whole numbers (the latency)
  double (*get)(const WorldFile& world) = nullptr;
  void (*set)(WorldFile& world, double value) = nullptr;  ///< rounds a whole value
};

/// Every calibrated value, in the order stride calibrate fits and reports them. Its nominal
/// value is a default WorldFile's.
const std::vector<CalibrationQuantity>& calibration_quantities();
/// The quantity of `name`, or null.
const CalibrationQuantity* find_calibration_quantity(std::string_view name);
/// The calibration `options` simulate, as a world file holds it (base: the faithful world).
WorldFile calibration_of(const WorldOptions& options);
/// An error naming the first value of `world` outside its range ("robot calibration: MX-106
/// torque scale must be in 0.1..3 x, got 7"), else ok.
Status check_calibration(const WorldFile& world);

/// Parses a world file's JSON; the error names the field.
Status parse_world_file(const nlohmann::json& doc, WorldFile& out);
/// Reads and parses a file; the error names the file and the field.
Status load_world_file(const std::filesystem::path& path, WorldFile& out);
nlohmann::json to_json(const WorldFile& world);

/// True if `text` names a world file rather than a named world (it ends in .json or has a /).
bool looks_like_world_file(const std::string& text);

}  // namespace stride::sim
