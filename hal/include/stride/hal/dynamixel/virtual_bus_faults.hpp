// Fault injection and counters shared by the emulated buses (VirtualBus, protocol 1.0, and
// VirtualBusV2, protocol 2.0): the `--fault` items of `stride vbus` and what the bus counts
// (`stride vbus --json`). Faults are seeded, so a run is reproducible.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <string>

#include "stride/core/status.hpp"

namespace stride::hal::dxl {

struct VirtualBusFaults {
  double drop_probability = 0.0;         ///< each status packet is lost with this probability
  double corrupt_probability = 0.0;      ///< each status packet gets one byte changed
  std::array<bool, 256> silent{};        ///< these IDs never answer
  std::array<bool, 256> overheat{};      ///< these servos report 85 deg C (limit 80)
  std::uint64_t start_after_cycles = 0;  ///< faults act after this many read cycles
  std::uint64_t seed = 1;

  /// Parses one `--fault` item: drop:P, corrupt:P, silent:ID, overheat:ID, start:CYCLES,
  /// seed:N. The error names the item.
  Status add(const std::string& spec);
};

struct VirtualBusCounters {
  std::uint64_t instructions = 0;   ///< valid instruction packets received
  std::uint64_t bad_packets = 0;    ///< damaged packets received (checksum / CRC)
  std::uint64_t replies = 0;        ///< status packets sent
  std::uint64_t error_replies = 0;  ///< status packets sent with a non-zero error byte / field
  std::uint64_t bulk_reads = 0;
  std::uint64_t sync_reads = 0;  ///< protocol 2.0 only
  std::uint64_t sync_writes = 0;
  std::uint64_t dropped = 0;    ///< replies dropped by fault injection
  std::uint64_t corrupted = 0;  ///< replies corrupted by fault injection
  std::uint64_t silenced = 0;   ///< replies withheld because a device is silent
};

/// Applies the drop and corrupt faults to one status packet about to be sent (call only while
/// faults are active). Returns false if the packet is lost; may change one of its bytes after
/// the header's first two. Counts what it did in `counters`.
bool inject_reply_faults(const VirtualBusFaults& faults, std::mt19937_64& rng,
                         std::span<std::uint8_t> packet, VirtualBusCounters& counters);

}  // namespace stride::hal::dxl
