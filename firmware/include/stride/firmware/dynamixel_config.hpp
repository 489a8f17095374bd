// Fills the Dynamixel HAL's plain per-servo parameters (direction, offset, model, name) from the
// firmware's ServoTable, so that hal stays independent of the firmware.
#pragma once

#include <array>
#include <string>

#include "stride/firmware/servo_table.hpp"
#include "stride/hal/dynamixel/dynamixel_robot.hpp"
#include "stride/hal/dynamixel/units.hpp"

namespace stride::fw {

std::array<hal::dxl::ServoCalibration, hal::kServoCount> servo_calibrations(
    const ServoTable& table);
std::array<std::string, hal::kServoCount> servo_names(const ServoTable& table);
/// DynamixelRobot options for the servos of `table` at `period_ns` (other fields default).
hal::dxl::DynamixelRobot::Options dynamixel_options(const ServoTable& table,
                                                    std::int64_t period_ns);

}  // namespace stride::fw
