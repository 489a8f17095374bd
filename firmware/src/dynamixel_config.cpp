// ServoTable -> Dynamixel HAL parameters (see dynamixel_config.hpp).
#include "stride/firmware/dynamixel_config.hpp"

namespace stride::fw {

std::array<hal::dxl::ServoCalibration, hal::kServoCount> servo_calibrations(
    const ServoTable& table) {
  std::array<hal::dxl::ServoCalibration, hal::kServoCount> out{};
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const ServoSpec& s = table[i];
    out[i].direction = s.direction;
    out[i].offset_rad = s.offset_rad;
    out[i].model = s.model == ServoModel::kMx64 ? hal::dxl::ServoModelId::kMx64
                                                : hal::dxl::ServoModelId::kMx106;
  }
  return out;
}

std::array<std::string, hal::kServoCount> servo_names(const ServoTable& table) {
  std::array<std::string, hal::kServoCount> out{};
  for (std::size_t i = 0; i < hal::kServoCount; ++i) out[i] = table[i].name;
  return out;
}

hal::dxl::DynamixelRobot::Options dynamixel_options(const ServoTable& table,
                                                    std::int64_t period_ns) {
  hal::dxl::DynamixelRobot::Options options;
  options.period_ns = period_ns;
  options.calibration = servo_calibrations(table);
  options.names = servo_names(table);
  return options;
}

}  // namespace stride::fw
