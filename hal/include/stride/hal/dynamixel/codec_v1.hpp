// Dynamixel protocol 1.0 packet encoders (instruction and status packets with the 1.0
// checksum). Every encoder writes into a caller-provided buffer and returns the number of bytes
// written, or 0 when the buffer is too small or the request cannot be encoded (a parameter
// block longer than 253 bytes). Nothing allocates.
//
// Wire format: FF FF ID LEN INSTR|ERROR P1..Pn CHECKSUM, LEN = n + 2,
// CHECKSUM = ~(ID + LEN + INSTR + P1 + ... + Pn) & 0xFF  (ROBOTIS e-manual, Protocol 1.0).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "stride/hal/dynamixel/protocol.hpp"

namespace stride::hal::dxl::v1 {

/// Bytes of a 1.0 packet carrying `param_count` parameters.
constexpr std::size_t packet_size(std::size_t param_count) {
  return param_count + 6;
}

/// ~(sum of bytes) & 0xFF over `bytes` (ID through the last parameter).
std::uint8_t checksum(std::span<const std::uint8_t> bytes);

std::size_t encode_instruction(std::span<std::uint8_t> out, std::uint8_t id,
                               std::uint8_t instruction, std::span<const std::uint8_t> params);
std::size_t encode_status(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t error,
                          std::span<const std::uint8_t> params);

std::size_t encode_ping(std::span<std::uint8_t> out, std::uint8_t id);
std::size_t encode_read(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t address,
                        std::uint8_t length);
std::size_t encode_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t address,
                         std::span<const std::uint8_t> data);
std::size_t encode_reg_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t address,
                             std::span<const std::uint8_t> data);
std::size_t encode_action(std::span<std::uint8_t> out, std::uint8_t id);
std::size_t encode_reset(std::span<std::uint8_t> out, std::uint8_t id);

/// SYNC_WRITE to the broadcast ID. `records` holds N records of [id, data_length bytes];
/// its size must be a multiple of data_length + 1.
std::size_t encode_sync_write(std::span<std::uint8_t> out, std::uint8_t start_address,
                              std::uint8_t data_length, std::span<const std::uint8_t> records);

/// BULK_READ (0x92) as the CM730 and MX 1.0 firmware serve it: parameter 0x00, then
/// [length, id, address] per device. Replies come back in list order.
std::size_t encode_bulk_read(std::span<std::uint8_t> out, std::span<const BulkReadEntry> entries);

}  // namespace stride::hal::dxl::v1
