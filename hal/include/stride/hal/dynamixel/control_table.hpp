// Control tables of the devices on the igus robot's bus, as data: MX-64 and MX-106 with the
// protocol 1.0 firmware and the protocol 2.0 firmware, the stock ROBOTIS CM730 and the CM730
// with NimbRo's firmware (16-bit IMU registers and a magnetometer, igus.md 6.5).
// Each register has a name, address, size, access, memory area, initial value and range
// (igus.md sections 6.2-6.4; ROBOTIS e-manual MX pages). The named address constants below are
// what code uses; the tables are what the virtual bus and `stride dxl` use.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "stride/hal/dynamixel/protocol.hpp"

namespace stride::hal::dxl {

enum class Access : std::uint8_t { kRead, kReadWrite };
enum class Memory : std::uint8_t { kEeprom, kRam };

struct Register {
  std::string_view name;
  std::uint16_t address = 0;
  std::uint8_t size = 1;  ///< bytes (1, 2 or 4), little-endian
  Access access = Access::kRead;
  Memory memory = Memory::kRam;
  std::uint32_t initial = 0;  ///< factory default / power-on value
  std::uint32_t min = 0;      ///< smallest value a WRITE may set
  std::uint32_t max = 0;      ///< largest value a WRITE may set
};

struct ControlTable {
  std::string_view model_name;  ///< "MX-64", "MX-106(2.0)", "CM730"
  std::uint16_t model_number = 0;
  Protocol protocol = Protocol::kV1;
  std::uint16_t size = 0;  ///< bytes of the table (addresses 0..size-1)
  std::span<const Register> registers;

  /// Register called `name` (exact, as in the e-manual with underscores: "goal_position").
  const Register* find(std::string_view name) const;
  /// Register starting at `address`, if any.
  const Register* at(std::uint16_t address) const;
  /// Register whose bytes cover `address`, if any.
  const Register* covering(std::uint16_t address) const;
};

const ControlTable& mx64_v1_table();
const ControlTable& mx106_v1_table();
const ControlTable& mx64_v2_table();
const ControlTable& mx106_v2_table();
const ControlTable& cm730_table();
/// The CM730 with NimbRo's firmware (cm730_nimbro below).
const ControlTable& cm730_nimbro_table();
/// The table with this model number and protocol, or nullptr.
const ControlTable* table_for_model(std::uint16_t model_number, Protocol protocol);

/// MX series, protocol 1.0 firmware (MX-64 / MX-106 share these addresses).
namespace mx1 {
inline constexpr std::uint8_t kModelNumber = 0;
inline constexpr std::uint8_t kFirmwareVersion = 2;
inline constexpr std::uint8_t kId = 3;
inline constexpr std::uint8_t kBaudRate = 4;
inline constexpr std::uint8_t kReturnDelayTime = 5;  ///< 2 us units
inline constexpr std::uint8_t kCwAngleLimit = 6;
inline constexpr std::uint8_t kCcwAngleLimit = 8;
inline constexpr std::uint8_t kTemperatureLimit = 11;
inline constexpr std::uint8_t kMinVoltageLimit = 12;
inline constexpr std::uint8_t kMaxVoltageLimit = 13;
inline constexpr std::uint8_t kMaxTorque = 14;
inline constexpr std::uint8_t kStatusReturnLevel = 16;  ///< 0 ping only, 1 reads, 2 all
inline constexpr std::uint8_t kAlarmLed = 17;
inline constexpr std::uint8_t kAlarmShutdown = 18;
inline constexpr std::uint8_t kTorqueEnable = 24;
inline constexpr std::uint8_t kLed = 25;
inline constexpr std::uint8_t kDGain = 26;
inline constexpr std::uint8_t kIGain = 27;
inline constexpr std::uint8_t kPGain = 28;
inline constexpr std::uint8_t kGoalPosition = 30;
inline constexpr std::uint8_t kMovingSpeed = 32;
inline constexpr std::uint8_t kTorqueLimit = 34;
inline constexpr std::uint8_t kPresentPosition = 36;
inline constexpr std::uint8_t kPresentSpeed = 38;
inline constexpr std::uint8_t kPresentLoad = 40;
inline constexpr std::uint8_t kPresentVoltage = 42;
inline constexpr std::uint8_t kPresentTemperature = 43;
inline constexpr std::uint8_t kRegistered = 44;
inline constexpr std::uint8_t kMoving = 46;
inline constexpr std::uint8_t kLock = 47;
inline constexpr std::uint8_t kPunch = 48;
inline constexpr std::uint8_t kTableSize = 74;
inline constexpr std::uint16_t kModelMx64 = 310;
inline constexpr std::uint16_t kModelMx106 = 320;
}  // namespace mx1

/// MX series, protocol 2.0 firmware.
namespace mx2 {
inline constexpr std::uint16_t kModelNumber = 0;
inline constexpr std::uint16_t kId = 7;
inline constexpr std::uint16_t kBaudRate = 8;
inline constexpr std::uint16_t kReturnDelayTime = 9;
inline constexpr std::uint16_t kOperatingMode = 11;  ///< 3 = position control (the default)
inline constexpr std::uint16_t kTemperatureLimit = 31;
inline constexpr std::uint16_t kMaxPositionLimit = 48;
inline constexpr std::uint16_t kMinPositionLimit = 52;
inline constexpr std::uint16_t kShutdown = 63;
inline constexpr std::uint16_t kTorqueEnable = 64;
inline constexpr std::uint16_t kStatusReturnLevel = 68;
inline constexpr std::uint16_t kRegisteredInstruction = 69;
inline constexpr std::uint16_t kHardwareErrorStatus = 70;
inline constexpr std::uint16_t kPositionDGain = 80;
inline constexpr std::uint16_t kPositionIGain = 82;
inline constexpr std::uint16_t kPositionPGain = 84;
inline constexpr std::uint16_t kProfileVelocity = 112;
inline constexpr std::uint16_t kGoalPosition = 116;
inline constexpr std::uint16_t kPresentVelocity = 128;
inline constexpr std::uint16_t kPresentPosition = 132;
inline constexpr std::uint16_t kPresentInputVoltage = 144;
inline constexpr std::uint16_t kPresentTemperature = 146;
inline constexpr std::uint16_t kTableSize = 147;
inline constexpr std::uint16_t kModelMx64 = 311;
inline constexpr std::uint16_t kModelMx106 = 321;
inline constexpr std::uint8_t kPositionControlMode = 3;  ///< Operating Mode value
}  // namespace mx2

/// Stock ROBOTIS CM730 (DARwIn-OP firmware) as NUbots uses it (igus.md 6.4).
namespace cm730 {
inline constexpr std::uint8_t kModelNumber = 0;
inline constexpr std::uint8_t kFirmwareVersion = 2;
inline constexpr std::uint8_t kId = 3;
inline constexpr std::uint8_t kBaudRate = 4;
inline constexpr std::uint8_t kReturnDelayTime = 5;
inline constexpr std::uint8_t kStatusReturnLevel = 16;
inline constexpr std::uint8_t kDxlPower = 24;
inline constexpr std::uint8_t kLedPanel = 25;
inline constexpr std::uint8_t kLedHead = 26;
inline constexpr std::uint8_t kLedEye = 28;
inline constexpr std::uint8_t kButton = 30;
inline constexpr std::uint8_t kGyroZ = 38;
inline constexpr std::uint8_t kGyroY = 40;
inline constexpr std::uint8_t kGyroX = 42;
inline constexpr std::uint8_t kAccelX = 44;
inline constexpr std::uint8_t kAccelY = 46;
inline constexpr std::uint8_t kAccelZ = 48;
inline constexpr std::uint8_t kVoltage = 50;
inline constexpr std::uint8_t kTableSize = 51;
/// Model number the stock CM730 reports (0x7300).
inline constexpr std::uint16_t kModel = 0x7300;
}  // namespace cm730

/// The CM730 with NimbRo's firmware (humanoid_op_ros CM_DXL_COM.h, igus.md 6.5): the same chips
/// read at 16 bits, signed, plus a 3-axis magnetometer. The 21 bytes from BUTTON (30) that the
/// stock table's bulk read takes cover BUTTON .. TEMPERATURE here too.
/// Model number: 0x7301, as NimbRo's register description of this board ("CM730_NOP") names
/// it; the stock board reports 0x7300, so the start-up model check tells the two apart.
namespace cm730_nimbro {
inline constexpr std::uint8_t kDxlPower = 24;
inline constexpr std::uint8_t kButton = 30;
inline constexpr std::uint8_t kBatteryVoltage = 31;  ///< 0.1 V
inline constexpr std::uint8_t kGyroX = 32;
inline constexpr std::uint8_t kGyroY = 34;
inline constexpr std::uint8_t kGyroZ = 36;
inline constexpr std::uint8_t kAccelX = 38;
inline constexpr std::uint8_t kAccelY = 40;
inline constexpr std::uint8_t kAccelZ = 42;
inline constexpr std::uint8_t kMagX = 44;
inline constexpr std::uint8_t kMagY = 46;
inline constexpr std::uint8_t kMagZ = 48;
inline constexpr std::uint8_t kTemperature = 50;
inline constexpr std::uint8_t kTableSize = 51;
inline constexpr std::uint16_t kModel = 0x7301;
}  // namespace cm730_nimbro

/// Which control table the CM730's firmware serves (the robot's choice: stride-fw --cm730).
enum class Cm730Profile : std::uint8_t {
  kStock,   ///< ROBOTIS firmware: 10-bit gyro and accelerometer, no magnetometer
  kNimbro,  ///< NimbRo's firmware: 16-bit gyro and accelerometer, magnetometer
};
/// "stock" or "nimbro".
const char* to_string(Cm730Profile profile);
/// Reads "stock" or "nimbro"; false for anything else.
bool parse_cm730_profile(std::string_view text, Cm730Profile& out);
/// The profile's control table and model number.
const ControlTable& cm730_table(Cm730Profile profile);

}  // namespace stride::hal::dxl
