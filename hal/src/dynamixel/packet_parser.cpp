// Streaming Dynamixel packet parser (see packet_parser.hpp).
#include "stride/hal/dynamixel/packet_parser.hpp"

#include <cstring>

#include "stride/hal/dynamixel/codec_v1.hpp"
#include "stride/hal/dynamixel/codec_v2.hpp"

namespace stride::hal::dxl {

std::size_t PacketParser::feed(std::span<const std::uint8_t> bytes) noexcept {
  if (head_ > 0 && (tail_ + bytes.size() > kCapacity || head_ > kCapacity / 2)) {
    std::memmove(buffer_.data(), buffer_.data() + head_, tail_ - head_);
    tail_ -= head_;
    head_ = 0;
  }
  std::size_t room = kCapacity - tail_;
  const std::size_t take = bytes.size() < room ? bytes.size() : room;
  if (take > 0) std::memcpy(buffer_.data() + tail_, bytes.data(), take);
  tail_ += take;
  return take;
}

void PacketParser::drop(std::size_t count) noexcept {
  head_ += count;
  stats_.discarded_bytes += count;
  if (head_ == tail_) head_ = tail_ = 0;
}

bool PacketParser::next(Packet& out) noexcept {
  return protocol_ == Protocol::kV1 ? next_v1(out) : next_v2(out);
}

bool PacketParser::next_v1(Packet& out) noexcept {
  for (;;) {
    const std::uint8_t* b = buffer_.data() + head_;
    const std::size_t n = tail_ - head_;
    if (n == 0) return false;
    if (b[0] != 0xFF) {
      drop(1);
      continue;
    }
    if (n < 2) return false;
    if (b[1] != 0xFF) {
      drop(1);
      continue;
    }
    if (n < 4) return false;
    const std::uint8_t id = b[2];
    const std::uint8_t length = b[3];
    if (id == 0xFF || length < 2) {
      ++stats_.bad_header;
      drop(1);
      continue;
    }
    const std::size_t total = 4U + length;
    if (n < total) return false;
    if (v1::checksum(std::span<const std::uint8_t>(b + 2, total - 3)) != b[total - 1]) {
      ++stats_.bad_checksum;
      last_bad_id_ = id;
      drop(1);
      continue;
    }
    out.protocol = Protocol::kV1;
    out.id = id;
    if (role_ == Role::kHost) {
      out.is_status = true;
      out.instruction = instruction::kStatus;
      out.error = b[4];
    } else {
      out.is_status = false;
      out.instruction = b[4];
      out.error = 0;
    }
    out.param_count = static_cast<std::uint16_t>(length - 2);
    std::memcpy(out.params.data(), b + 5, out.param_count);
    head_ += total;
    if (head_ == tail_) head_ = tail_ = 0;
    ++stats_.packets;
    return true;
  }
}

bool PacketParser::next_v2(Packet& out) noexcept {
  static constexpr std::uint8_t kHeader[4] = {0xFF, 0xFF, 0xFD, 0x00};
  for (;;) {
    const std::uint8_t* b = buffer_.data() + head_;
    const std::size_t n = tail_ - head_;
    if (n == 0) return false;
    // Header prefix match: drop a byte as soon as the prefix seen so far cannot be a header.
    bool prefix_ok = true;
    const std::size_t check = n < 4 ? n : 4;
    for (std::size_t i = 0; i < check; ++i) {
      if (b[i] != kHeader[i]) {
        prefix_ok = false;
        break;
      }
    }
    if (!prefix_ok) {
      drop(1);
      continue;
    }
    if (n < 7) return false;
    const std::uint8_t id = b[4];
    const std::size_t length = read_u16(b + 5);
    const std::size_t total = 7 + length;
    // Length covers instruction + params + CRC: at least 3; a status needs the error byte too.
    if (id == 0xFD || id == 0xFF || length < 3 || total > kMaxPacketBytes) {
      ++stats_.bad_header;
      drop(1);
      continue;
    }
    if (n < total) return false;
    const std::uint16_t crc = v2::crc16(std::span<const std::uint8_t>(b, total - 2));
    if (crc != read_u16(b + total - 2)) {
      ++stats_.bad_checksum;
      last_bad_id_ = id;
      drop(1);
      continue;
    }
    // Un-stuff the instruction + parameter field: FF FF FD FD -> FF FF FD.
    std::array<std::uint8_t, kMaxPacketBytes> body{};
    std::size_t body_n = 0;
    const std::size_t body_end = total - 2;
    for (std::size_t i = 7; i < body_end; ++i) {
      body[body_n++] = b[i];
      if (body_n >= 3 && body[body_n - 3] == 0xFF && body[body_n - 2] == 0xFF &&
          body[body_n - 1] == 0xFD && i + 1 < body_end && b[i + 1] == 0xFD) {
        ++i;  // skip the stuffing byte
      }
    }
    const std::uint8_t code = body[0];
    const bool is_status = code == instruction::kStatus;
    if (is_status && body_n < 2) {
      ++stats_.bad_header;
      drop(1);
      continue;
    }
    out.protocol = Protocol::kV2;
    out.id = id;
    out.instruction = code;
    out.is_status = is_status;
    out.error = is_status ? body[1] : 0;
    const std::size_t first = is_status ? 2 : 1;
    out.param_count = static_cast<std::uint16_t>(body_n - first);
    std::memcpy(out.params.data(), body.data() + first, out.param_count);
    head_ += total;
    if (head_ == tail_) head_ = tail_ = 0;
    ++stats_.packets;
    return true;
  }
}

}  // namespace stride::hal::dxl
