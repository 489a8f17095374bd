// Dynamixel protocol 2.0 packet encoders: header FF FF FD 00, 16-bit length, CRC-16
// (polynomial 0x8005, as the ROBOTIS e-manual "CRC calculation" page defines it) and byte
// stuffing (FF FF FD -> FF FF FD FD inside the instruction and parameter fields).
// Every encoder writes into a caller-provided buffer and returns the bytes written, or 0 when
// the buffer is too small or the packet would exceed kMaxPacketBytes. Nothing allocates.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "stride/hal/dynamixel/protocol.hpp"

namespace stride::hal::dxl::v2 {

/// CRC-16 (poly 0x8005, init `crc`, no reflection) over `bytes`.
std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t crc = 0);

/// Bytes of a 2.0 packet whose instruction+parameter field holds `body` bytes after stuffing.
constexpr std::size_t packet_size(std::size_t stuffed_body) {
  return stuffed_body + 9;
}

std::size_t encode_instruction(std::span<std::uint8_t> out, std::uint8_t id,
                               std::uint8_t instruction, std::span<const std::uint8_t> params);
/// Status packet: instruction 0x55, error field, parameters.
std::size_t encode_status(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t error,
                          std::span<const std::uint8_t> params);

std::size_t encode_ping(std::span<std::uint8_t> out, std::uint8_t id);
std::size_t encode_read(std::span<std::uint8_t> out, std::uint8_t id, std::uint16_t address,
                        std::uint16_t length);
std::size_t encode_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint16_t address,
                         std::span<const std::uint8_t> data);
std::size_t encode_reg_write(std::span<std::uint8_t> out, std::uint8_t id, std::uint16_t address,
                             std::span<const std::uint8_t> data);
std::size_t encode_action(std::span<std::uint8_t> out, std::uint8_t id);
/// FACTORY_RESET with option 0xFF (all), 0x01 (all but ID) or 0x02 (all but ID and baud).
std::size_t encode_factory_reset(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t option);
std::size_t encode_reboot(std::span<std::uint8_t> out, std::uint8_t id);
/// SYNC_READ of `length` bytes at `address` from every id in `ids`.
std::size_t encode_sync_read(std::span<std::uint8_t> out, std::uint16_t address,
                             std::uint16_t length, std::span<const std::uint8_t> ids);
/// SYNC_WRITE; `records` holds N records of [id, data_length bytes].
std::size_t encode_sync_write(std::span<std::uint8_t> out, std::uint16_t address,
                              std::uint16_t data_length, std::span<const std::uint8_t> records);
/// BULK_READ: [id, address L/H, length L/H] per device.
std::size_t encode_bulk_read(std::span<std::uint8_t> out, std::span<const BulkReadEntry> entries);

}  // namespace stride::hal::dxl::v2
