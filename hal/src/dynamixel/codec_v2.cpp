// Dynamixel protocol 2.0 encoders (see codec_v2.hpp).
#include "stride/hal/dynamixel/codec_v2.hpp"

#include <array>

namespace stride::hal::dxl::v2 {

namespace {

// CRC-16 table for polynomial 0x8005, MSB first (the ROBOTIS "CRC calculation" algorithm).
constexpr std::array<std::uint16_t, 256> make_crc_table() {
  std::array<std::uint16_t, 256> table{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned crc = i << 8;
    for (int bit = 0; bit < 8; ++bit) {
      crc = (crc & 0x8000U) != 0 ? ((crc << 1) ^ 0x8005U) : (crc << 1);
    }
    table[i] = static_cast<std::uint16_t>(crc & 0xFFFFU);
  }
  return table;
}
constexpr std::array<std::uint16_t, 256> kCrcTable = make_crc_table();

// Builds a packet from up to two parameter blocks (head then params), stuffing as it goes.
std::size_t encode(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t code,
                   std::span<const std::uint8_t> head, std::span<const std::uint8_t> params,
                   bool with_error = false, std::uint8_t error = 0) {
  if (out.size() < 10) return 0;
  const std::size_t limit = out.size() < kMaxPacketBytes ? out.size() : kMaxPacketBytes;
  out[0] = 0xFF;
  out[1] = 0xFF;
  out[2] = 0xFD;
  out[3] = 0x00;
  out[4] = id;
  std::size_t i = 7;
  std::size_t body_start = i;
  auto put = [&](std::uint8_t b) -> bool {
    if (i + 1 + 2 > limit) return false;  // room for this byte, a possible stuffing byte later
    out[i++] = b;
    if (i - body_start >= 3 && out[i - 3] == 0xFF && out[i - 2] == 0xFF && out[i - 1] == 0xFD) {
      if (i + 1 + 2 > limit) return false;
      out[i++] = 0xFD;
    }
    return true;
  };
  if (!put(code)) return 0;
  if (with_error && !put(error)) return 0;
  for (const std::uint8_t b : head) {
    if (!put(b)) return 0;
  }
  for (const std::uint8_t b : params) {
    if (!put(b)) return 0;
  }
  const std::size_t length = i - body_start + 2;
  out[5] = static_cast<std::uint8_t>(length & 0xFFU);
  out[6] = static_cast<std::uint8_t>(length >> 8);
  const std::uint16_t crc = crc16(out.first(i));
  out[i++] = static_cast<std::uint8_t>(crc & 0xFFU);
  out[i++] = static_cast<std::uint8_t>(crc >> 8);
  return i;
}

std::array<std::uint8_t, 4> addr_len(std::uint16_t address, std::uint16_t length) {
  return {static_cast<std::uint8_t>(address & 0xFFU), static_cast<std::uint8_t>(address >> 8),
          static_cast<std::uint8_t>(length & 0xFFU), static_cast<std::uint8_t>(length >> 8)};
}

}  // namespace

std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
  for (const std::uint8_t b : bytes) {
    const unsigned index = ((static_cast<unsigned>(crc) >> 8) ^ b) & 0xFFU;
    crc = static_cast<std::uint16_t>((static_cast<unsigned>(crc) << 8) ^ kCrcTable[index]);
  }
  return crc;
}

std::size_t encode_instruction(std::span<std::uint8_t> out, std::uint8_t id,
                               std::uint8_t instruction, std::span<const std::uint8_t> params) {
  return encode(out, id, instruction, {}, params);
}

std::size_t encode_status(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t error,
                          std::span<const std::uint8_t> params) {
  return encode(out, id, instruction::kStatus, {}, params, true, error);
}

std::size_t encode_ping(std::span<std::uint8_t> out, std::uint8_t id) {
  return encode(out, id, instruction::kPing, {}, {});
}

std::size_t encode_read(std::span<std::uint8_t> out, std::uint8_t id, std::uint16_t address,
                        std::uint16_t length) {
  const auto p = addr_len(address, length);
  return encode(out, id, instruction::kRead, p, {});
}

std::size_t encode_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint16_t address,
                         std::span<const std::uint8_t> data) {
  const std::array<std::uint8_t, 2> head{static_cast<std::uint8_t>(address & 0xFFU),
                                         static_cast<std::uint8_t>(address >> 8)};
  return encode(out, id, instruction::kWrite, head, data);
}

std::size_t encode_reg_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint16_t address,
                             std::span<const std::uint8_t> data) {
  const std::array<std::uint8_t, 2> head{static_cast<std::uint8_t>(address & 0xFFU),
                                         static_cast<std::uint8_t>(address >> 8)};
  return encode(out, id, instruction::kRegWrite, head, data);
}

std::size_t encode_action(std::span<std::uint8_t> out, std::uint8_t id) {
  return encode(out, id, instruction::kAction, {}, {});
}

std::size_t encode_factory_reset(std::span<std::uint8_t> out, std::uint8_t id,
                                 std::uint8_t option) {
  const std::array<std::uint8_t, 1> p{option};
  return encode(out, id, instruction::kReset, p, {});
}

std::size_t encode_reboot(std::span<std::uint8_t> out, std::uint8_t id) {
  return encode(out, id, instruction::kReboot, {}, {});
}

std::size_t encode_sync_read(std::span<std::uint8_t> out, std::uint16_t address,
                             std::uint16_t length, std::span<const std::uint8_t> ids) {
  const auto p = addr_len(address, length);
  return encode(out, kBroadcastId, instruction::kSyncRead, p, ids);
}

std::size_t encode_sync_write(std::span<std::uint8_t> out, std::uint16_t address,
                              std::uint16_t data_length, std::span<const std::uint8_t> records) {
  if (data_length == 0 || records.size() % (data_length + 1U) != 0) return 0;
  const auto p = addr_len(address, data_length);
  return encode(out, kBroadcastId, instruction::kSyncWrite, p, records);
}

std::size_t encode_bulk_read(std::span<std::uint8_t> out, std::span<const BulkReadEntry> entries) {
  std::array<std::uint8_t, kMaxParams> params{};
  if (entries.size() * 5 > params.size()) return 0;
  std::size_t i = 0;
  for (const BulkReadEntry& e : entries) {
    params[i++] = e.id;
    params[i++] = static_cast<std::uint8_t>(e.address & 0xFFU);
    params[i++] = static_cast<std::uint8_t>(e.address >> 8);
    params[i++] = static_cast<std::uint8_t>(e.length & 0xFFU);
    params[i++] = static_cast<std::uint8_t>(e.length >> 8);
  }
  return encode(out, kBroadcastId, instruction::kBulkRead, {},
                std::span<const std::uint8_t>(params.data(), i));
}

}  // namespace stride::hal::dxl::v2
