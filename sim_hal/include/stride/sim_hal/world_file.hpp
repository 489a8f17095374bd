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
// Unknown fields and out-of-range values are errors naming the field.
#pragma once

#include <filesystem>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::sim {

struct WorldFile {
  WorldPreset base = WorldPreset::kFaithful;
  double supply_voltage_v = kNominalSupplyVoltage;  ///< the robot's battery (WorldOptions::battery_voltage_v)
  RobotCalibration robot;
  Eigen::Vector3d gyro_bias_rad_s = Eigen::Vector3d::Zero();  ///< fixed IMU biases, torso frame
  Eigen::Vector3d accel_bias_mps2 = Eigen::Vector3d::Zero();
  nlohmann::json calibration = nlohmann::json::object();  ///< provenance (not interpreted)

  /// Sets the base world's servo law, IMU chain and contact, then the calibration.
  void apply(WorldOptions& options) const;
  /// Sets the calibration alone (the voltage, RobotCalibration, the IMU's fixed biases).
  void apply_calibration(WorldOptions& options) const;
};

/// Parses a world file's JSON; the error names the field.
Status parse_world_file(const nlohmann::json& doc, WorldFile& out);
/// Reads and parses a file; the error names the file and the field.
Status load_world_file(const std::filesystem::path& path, WorldFile& out);
nlohmann::json to_json(const WorldFile& world);

/// True if `text` names a world file rather than a named world (it ends in .json or has a /).
bool looks_like_world_file(const std::string& text);

}  // namespace stride::sim
