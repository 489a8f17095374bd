// ServoTable: the per-servo facts that are data, not code (firmware/config/servo_table.json):
// Dynamixel ID, name, model, direction, zero offset and position limits of the 20 servos.
//
// Joint angles everywhere in Stride are URDF joint angles [rad]. The Dynamixel HAL converts with
//   ticks = direction * (angle - offset_rad) * 4096 / (2 pi) + 2048.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "stride/core/status.hpp"
#include "stride/hal/types.hpp"

namespace stride::fw {

enum class ServoModel : std::uint8_t { kMx64, kMx106 };

std::string_view to_string(ServoModel model);

struct ServoSpec {
  std::uint8_t id = 0;  ///< Dynamixel ID 1..20 (index = id - 1)
  std::string name;     ///< lower-case joint name, e.g. "r_knee"
  ServoModel model = ServoModel::kMx106;
  int direction = 1;        ///< +1 or -1: servo sense relative to the URDF joint axis
  double offset_rad = 0.0;  ///< URDF angle at which the servo reads its centre (2048)
  double min_rad = 0.0;     ///< lower position limit (URDF angle)
  double max_rad = 0.0;     ///< upper position limit (URDF angle)
};

class ServoTable {
 public:
  /// Loads and validates a servo table file: exactly the IDs 1..20, unique names, a known model,
  /// direction +-1, a finite offset within [-pi, pi], min < max. The error names the file and
  /// the field, e.g. "servo_table.json: servos[3].direction: must be 1 or -1, got 0".
  static Status load(const std::filesystem::path& path, ServoTable& out);

  /// The table shipped in firmware/config/servo_table.json (throws std::runtime_error with the
  /// loader's message if that file is missing or broken).
  static const ServoTable& defaults();
  /// Path of the shipped table.
  static std::filesystem::path default_path();

  const ServoSpec& operator[](std::size_t index) const { return servos_[index]; }
  const std::array<ServoSpec, hal::kServoCount>& servos() const { return servos_; }
  /// Index 0..19 of the servo called `name`, if any.
  std::optional<std::size_t> index_of(std::string_view name) const;

 private:
  std::array<ServoSpec, hal::kServoCount> servos_{};
};

}  // namespace stride::fw
