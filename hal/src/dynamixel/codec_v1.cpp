// Dynamixel protocol 1.0 encoders (see codec_v1.hpp).
#include "stride/hal/dynamixel/codec_v1.hpp"

#include <array>

namespace stride::hal::dxl::v1 {

std::uint8_t checksum(std::span<const std::uint8_t> bytes) {
  unsigned sum = 0;
  for (const std::uint8_t b : bytes) sum += b;
  return static_cast<std::uint8_t>(~sum & 0xFFU);
}

namespace {

// Writes FF FF id len code then `parts` parameter blocks, then the checksum.
std::size_t encode(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t code,
                   std::span<const std::uint8_t> head, std::span<const std::uint8_t> params) {
  const std::size_t param_count = head.size() + params.size();
  if (param_count > 253) return 0;
  const std::size_t total = packet_size(param_count);
  if (out.size() < total) return 0;
  out[0] = 0xFF;
  out[1] = 0xFF;
  out[2] = id;
  out[3] = static_cast<std::uint8_t>(param_count + 2);
  out[4] = code;
  std::size_t i = 5;
  for (const std::uint8_t b : head) out[i++] = b;
  for (const std::uint8_t b : params) out[i++] = b;
  out[i] = checksum(out.subspan(2, i - 2));
  return total;
}

}  // namespace

std::size_t encode_instruction(std::span<std::uint8_t> out, std::uint8_t id,
                               std::uint8_t instruction, std::span<const std::uint8_t> params) {
  return encode(out, id, instruction, {}, params);
}

std::size_t encode_status(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t error,
                          std::span<const std::uint8_t> params) {
  return encode(out, id, error, {}, params);
}

std::size_t encode_ping(std::span<std::uint8_t> out, std::uint8_t id) {
  return encode(out, id, instruction::kPing, {}, {});
}

std::size_t encode_read(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t address,
                        std::uint8_t length) {
  const std::array<std::uint8_t, 2> p{address, length};
  return encode(out, id, instruction::kRead, p, {});
}

std::size_t encode_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t address,
                         std::span<const std::uint8_t> data) {
  const std::array<std::uint8_t, 1> head{address};
  return encode(out, id, instruction::kWrite, head, data);
}

std::size_t encode_reg_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t address,
                             std::span<const std::uint8_t> data) {
  const std::array<std::uint8_t, 1> head{address};
  return encode(out, id, instruction::kRegWrite, head, data);
}

std::size_t encode_action(std::span<std::uint8_t> out, std::uint8_t id) {
  return encode(out, id, instruction::kAction, {}, {});
}

std::size_t encode_reset(std::span<std::uint8_t> out, std::uint8_t id) {
  return encode(out, id, instruction::kReset, {}, {});
}

std::size_t encode_sync_write(std::span<std::uint8_t> out, std::uint8_t start_address,
                              std::uint8_t data_length, std::span<const std::uint8_t> records) {
  if (data_length == 0 || records.size() % (data_length + 1U) != 0) return 0;
  const std::array<std::uint8_t, 2> head{start_address, data_length};
  return encode(out, kBroadcastId, instruction::kSyncWrite, head, records);
}

std::size_t encode_bulk_read(std::span<std::uint8_t> out, std::span<const BulkReadEntry> entries) {
  const std::size_t param_count = 1 + 3 * entries.size();
  if (param_count > 253) return 0;
  const std::size_t total = packet_size(param_count);
  if (out.size() < total) return 0;
  std::array<std::uint8_t, 253> params{};
  params[0] = 0x00;
  std::size_t i = 1;
  for (const BulkReadEntry& e : entries) {
    if (e.length > 0xFF || e.address > 0xFF) return 0;
    params[i++] = static_cast<std::uint8_t>(e.length);
    params[i++] = e.id;
    params[i++] = static_cast<std::uint8_t>(e.address);
  }
  return encode(out, kBroadcastId, instruction::kBulkRead, {},
                std::span<const std::uint8_t>(params.data(), param_count));
}

}  // namespace stride::hal::dxl::v1
