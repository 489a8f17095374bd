// The flight log's header block: what a log needs to be read and trusted on its own (firmware
// version, loop period, servo table, every parameter with its value at start, and the hash of
// the robot description the firmware ran with).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/robot_description.hpp"
#include "stride/firmware/servo_table.hpp"

namespace stride::fw::flight_log {

/// The firmware's version ("0.1.0") and the git commit it was configured from ("" unknown).
std::string_view firmware_version() noexcept;
std::string_view firmware_git() noexcept;

/// The servo table as JSON: [{id, name, model, direction, offset_rad, min_rad, max_rad}, ...].
nlohmann::json servo_table_json(const ServoTable& servos);

/// Hash of the robot description the firmware runs with: its servo table and its rigid-body
/// model (robot_description.json, RobotDescription). "fnv1a64:" and 16 hex digits of the FNV-1a
/// 64-bit hash of servo_table_json(servos).dump() (compact, keys sorted) followed by the 16 hex
/// digits of robot.hash() (FNV-1a of the description file's text).
std::string robot_description_hash(const ServoTable& servos, const RobotDescription& robot);

struct HeaderInputs {
  const ParameterStore* params = nullptr;
  const ServoTable* servos = nullptr;
  std::filesystem::path servo_table_file;
  std::int64_t period_ns = 0;
  std::string hal;                          ///< HAL backend name (serial, sim, test)
  std::filesystem::path params_file;        ///< --params FILE applied at start-up ("" none)
  const RobotDescription* robot = nullptr;  ///< the rigid-body model (required)
  std::filesystem::path robot_description_file;
};

/// The header block's JSON (see FLIGHT_LOG.md for every field).
nlohmann::json make_header(const HeaderInputs& inputs);

}  // namespace stride::fw::flight_log
