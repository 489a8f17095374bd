// Diagnostics: health and timing counters a HAL keeps about its bus or simulation.
#pragma once

#include <array>
#include <cstdint>

#include "stride/hal/types.hpp"

namespace stride::hal {

/// Per-device counters, cumulative since start-up.
struct DeviceDiagnostics {
  std::uint32_t replies = 0;          ///< valid replies received
  std::uint32_t timeouts = 0;         ///< replies missing or incomplete
  std::uint32_t corrupt_replies = 0;  ///< bad checksum, length or id
  std::uint32_t error_replies = 0;    ///< valid replies with error bits set
  std::uint32_t consecutive_failures = 0;
  std::uint8_t last_error_flags = 0;
  DeviceHealth health = DeviceHealth::kMissing;
};

/// Whole-HAL diagnostics, cumulative since start-up. Index 0..19 are the servos, index 20 the
/// CM730 (kCm730DiagIndex).
struct Diagnostics {
  static constexpr std::size_t kCm730DiagIndex = kServoCount;
  std::array<DeviceDiagnostics, kServoCount + 1> devices{};
  std::uint64_t cycles = 0;     ///< completed read/write cycles
  std::int64_t last_tx_ns = 0;  ///< time spent transmitting in the last cycle [ns]
  std::int64_t last_rx_ns = 0;  ///< time spent waiting for/receiving replies [ns]
  std::int64_t max_tx_ns = 0;
  std::int64_t max_rx_ns = 0;
  std::uint64_t bytes_tx = 0;  ///< bytes written to the bus
  std::uint64_t bytes_rx = 0;  ///< bytes read from the bus
};

}  // namespace stride::hal
