// Dynamixel protocol vocabulary shared by the 1.0 and 2.0 codecs: versions, instruction codes,
// special IDs and the size limits of the fixed packet buffers.
//
// Sources: ROBOTIS e-manual "Protocol 1.0" and "Protocol 2.0" pages (instruction tables).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace stride::hal::dxl {

enum class Protocol : std::uint8_t { kV1 = 1, kV2 = 2 };

/// Instruction codes (identical in 1.0 and 2.0 where both define them).
namespace instruction {
inline constexpr std::uint8_t kPing = 0x01;
inline constexpr std::uint8_t kRead = 0x02;
inline constexpr std::uint8_t kWrite = 0x03;
inline constexpr std::uint8_t kRegWrite = 0x04;
inline constexpr std::uint8_t kAction = 0x05;
inline constexpr std::uint8_t kReset = 0x06;   ///< 1.0 RESET, 2.0 FACTORY_RESET
inline constexpr std::uint8_t kReboot = 0x08;  ///< 2.0 only
inline constexpr std::uint8_t kStatus = 0x55;  ///< 2.0 status packets
inline constexpr std::uint8_t kSyncRead = 0x82;
inline constexpr std::uint8_t kSyncWrite = 0x83;
inline constexpr std::uint8_t kBulkRead = 0x92;
inline constexpr std::uint8_t kBulkWrite = 0x93;
}  // namespace instruction

/// Broadcast ID: every device executes the instruction; only PING (2.0) is answered.
inline constexpr std::uint8_t kBroadcastId = 0xFE;

/// Largest packet (bytes on the wire, 2.0 stuffing included) the codec builds or accepts.
/// A 1.0 packet is at most 4 + 255 bytes; 2.0 packets longer than this are rejected.
inline constexpr std::size_t kMaxPacketBytes = 1024;
/// Largest parameter block of a decoded packet.
inline constexpr std::size_t kMaxParams = kMaxPacketBytes;

/// Protocol 2.0 status error field (bits 0..6 = error number, bit 7 = hardware alert).
namespace v2_error {
inline constexpr std::uint8_t kResultFail = 0x01;
inline constexpr std::uint8_t kInstruction = 0x02;
inline constexpr std::uint8_t kCrc = 0x03;
inline constexpr std::uint8_t kDataRange = 0x04;
inline constexpr std::uint8_t kDataLength = 0x05;
inline constexpr std::uint8_t kDataLimit = 0x06;
inline constexpr std::uint8_t kAccess = 0x07;
inline constexpr std::uint8_t kAlert = 0x80;
}  // namespace v2_error

/// One decoded packet (instruction or status), held in a fixed buffer: no allocation.
struct Packet {
  Protocol protocol = Protocol::kV1;
  std::uint8_t id = 0;
  /// Instruction code; 0x55 (kStatus) for status packets of either protocol.
  std::uint8_t instruction = 0;
  /// Status packets: the error byte (1.0 error bits, or the 2.0 error field). 0 otherwise.
  std::uint8_t error = 0;
  bool is_status = false;
  std::uint16_t param_count = 0;  ///< parameters after un-stuffing (2.0), error byte excluded
  std::array<std::uint8_t, kMaxParams> params{};

  std::span<const std::uint8_t> parameters() const { return {params.data(), param_count}; }
};

/// One device's entry of a BULK_READ (1.0 as the CM730 serves it, and 2.0).
struct BulkReadEntry {
  std::uint8_t id = 0;
  std::uint16_t address = 0;
  std::uint16_t length = 0;
};

/// Little-endian helpers (both protocols are little-endian).
constexpr std::uint16_t read_u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
constexpr std::uint32_t read_u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

}  // namespace stride::hal::dxl
