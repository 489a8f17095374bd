// Basic HAL vocabulary: integer control ticks, servo indexing and device health.
//
// Time in Stride is an integer tick count k; the wall or simulated time of tick k is
// t_k = k * period_ns. Only a HAL implementation maps ticks to a clock.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stride::hal {

/// Control-loop time: the number of loop periods since the loop started (tick 0).
using Tick = std::int64_t;

/// Number of servos on the igus humanoid (Dynamixel IDs 1..20 in DARwIn order).
inline constexpr std::size_t kServoCount = 20;

/// Dynamixel ID of the CM730 sub-controller.
inline constexpr std::uint8_t kCm730Id = 200;

/// Servo index 0..19 for Dynamixel ID 1..20 (index = id - 1).
constexpr std::size_t servo_index(std::uint8_t dynamixel_id) {
  return dynamixel_id - 1U;
}

/// Health of one bus device as seen by the HAL in the latest cycle.
enum class DeviceHealth : std::uint8_t {
  kOk = 0,       ///< replied in time with a valid packet
  kError = 1,    ///< replied, but with Dynamixel error bits set
  kTimeout = 2,  ///< no (complete) reply within the cycle's budget this tick
  kMissing = 3,  ///< not found at start-up or disabled after persistent failure
};

/// Dynamixel protocol 1.0 status error bits (also used for 2.0 hardware errors, mapped).
namespace error_bits {
inline constexpr std::uint8_t kInputVoltage = 1U << 0;
inline constexpr std::uint8_t kAngleLimit = 1U << 1;
inline constexpr std::uint8_t kOverheating = 1U << 2;
inline constexpr std::uint8_t kRange = 1U << 3;
inline constexpr std::uint8_t kChecksum = 1U << 4;
inline constexpr std::uint8_t kOverload = 1U << 5;
inline constexpr std::uint8_t kInstruction = 1U << 6;
}  // namespace error_bits

}  // namespace stride::hal
