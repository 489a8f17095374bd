// SensorFrame: everything the controller learns about the robot in one control cycle.
//
// Fields follow the CM730/MX control tables (igus.md section 6) and the seed's DarwinSensors
// message (igus.md section 7.1), converted to SI units. Joint angles are URDF joint angles
// (right-hand rule about the joint axis); the servo table's direction and zero offset are
// applied by the HAL, never by the controller.
#pragma once

#include <array>
#include <cstdint>

#include "stride/hal/types.hpp"

namespace stride::hal {

/// State of one servo as read back in this cycle (DarwinSensors per-servo block).
struct ServoState {
  double position_rad = 0.0;       ///< present position, URDF joint angle [rad]
  double speed_rad_s = 0.0;        ///< present speed [rad/s]
  double load = 0.0;               ///< present load, signed fraction of max torque [-1, 1]
  double voltage_v = 0.0;          ///< present supply voltage [V]
  double temperature_c = 0.0;      ///< present internal temperature [deg C]
  double goal_position_rad = 0.0;  ///< goal position last written [rad]
  double p_gain = 0.0;             ///< P gain register (MX 1.0 units, Kp = P/8)
  double i_gain = 0.0;             ///< I gain register
  double d_gain = 0.0;             ///< D gain register
  double torque_limit = 0.0;       ///< torque limit, fraction of max torque [0, 1]
  bool torque_enabled = false;     ///< torque enable register
  std::uint8_t error_flags = 0;    ///< Dynamixel status error bits (hal::error_bits)
  DeviceHealth health = DeviceHealth::kMissing;
};

/// The CM730 sub-controller: IMU in the torso frame (x forward, y left, z up).
struct Cm730State {
  /// Specific force [m/s^2] in the torso frame: upright and still reads (0, 0, +9.81).
  std::array<double, 3> accel_mps2{0.0, 0.0, 0.0};
  /// Angular rate [rad/s] about the torso x, y, z axes.
  std::array<double, 3> gyro_rad_s{0.0, 0.0, 0.0};
  /// Magnetic field [gauss] in the torso frame, when the CM730 has a magnetometer (NimbRo's
  /// firmware, igus.md 6.5); zero otherwise.
  std::array<double, 3> mag_gauss{0.0, 0.0, 0.0};
  bool has_magnetometer = false;  ///< mag_gauss holds a reading
  double voltage_v = 0.0;         ///< battery voltage [V]
  std::uint8_t buttons = 0;       ///< button bit field
  std::uint8_t error_flags = 0;   ///< Dynamixel status error bits of the CM730
  DeviceHealth health = DeviceHealth::kMissing;
};

/// One control cycle's sensor readings. Plain data, fixed size, cheap to copy.
struct SensorFrame {
  Tick tick = 0;  ///< the tick at which these readings were taken
  std::array<ServoState, kServoCount> servos{};
  Cm730State cm730{};
};

}  // namespace stride::hal
