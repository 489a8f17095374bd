// PacketParser: a streaming Dynamixel 1.0/2.0 packet parser with a fixed internal buffer.
//
// Bytes may arrive in any chunking. The parser looks for a header, checks the ID, the length
// bounds and the checksum (1.0) or CRC-16 (2.0), removes 2.0 byte stuffing, and hands out one
// packet at a time. After garbage or a rejected packet it drops one byte and searches again, so
// a valid packet that follows damaged bytes is still found. It never reads out of bounds and
// allocates nothing after construction.
//
//   parser.feed(bytes) -> number of bytes taken (all of them unless the buffer is full);
//   while (parser.next(packet)) { ... }   // call after every feed
//
// 1.0 instruction and status packets look alike on the wire, so the parser is told which side
// it sits on (Role): a host reads status packets, a device (the virtual bus) reads instructions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "stride/hal/dynamixel/protocol.hpp"

namespace stride::hal::dxl {

class PacketParser {
 public:
  enum class Role : std::uint8_t { kHost, kDevice };

  struct Stats {
    std::uint64_t packets = 0;          ///< packets handed out
    std::uint64_t bad_checksum = 0;     ///< complete packets with a wrong checksum/CRC
    std::uint64_t bad_header = 0;       ///< header with an invalid ID or length
    std::uint64_t discarded_bytes = 0;  ///< bytes dropped while resynchronising
  };

  PacketParser(Protocol protocol, Role role) : protocol_(protocol), role_(role) {}

  /// Appends as many of `bytes` as fit into the buffer; returns how many were taken.
  std::size_t feed(std::span<const std::uint8_t> bytes) noexcept;

  /// Extracts the next complete valid packet into `out`. Returns false when more bytes are
  /// needed. Call repeatedly after each feed().
  bool next(Packet& out) noexcept;

  /// Gives up on the incomplete packet at the front of the buffer (its declared length may have
  /// been damaged) by dropping one byte, so that next() searches again. Call when no more bytes
  /// will come (a read timed out). Returns false when the buffer is empty.
  bool skip_incomplete() noexcept {
    if (head_ == tail_) return false;
    drop(1);
    return true;
  }

  /// Drops buffered bytes (e.g. before a new transaction).
  void reset() noexcept { head_ = tail_ = 0; }

  std::size_t buffered() const noexcept { return tail_ - head_; }
  const Stats& stats() const noexcept { return stats_; }
  /// ID byte of the last packet rejected for its checksum (for attributing corruption).
  std::uint8_t last_bad_id() const noexcept { return last_bad_id_; }
  Protocol protocol() const noexcept { return protocol_; }

 private:
  static constexpr std::size_t kCapacity = 2 * kMaxPacketBytes;
  void drop(std::size_t count) noexcept;
  bool next_v1(Packet& out) noexcept;
  bool next_v2(Packet& out) noexcept;

  Protocol protocol_;
  Role role_;
  std::array<std::uint8_t, kCapacity> buffer_{};
  std::size_t head_ = 0;
  std::size_t tail_ = 0;
  Stats stats_{};
  std::uint8_t last_bad_id_ = 0;
};

}  // namespace stride::hal::dxl
