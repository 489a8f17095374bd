// libFuzzer target: every 1.0 and 2.0 encoder (codec_v1, codec_v2) with arguments, parameter
// blocks and output buffer sizes taken from the input. Oracle, independent of the codecs:
// an encoder returns the exact packet size when the packet fits both the buffer and the
// protocol's limits (computed here, 2.0 stuffing included), 0 otherwise; and what it wrote
// parses back (PacketParser) to the expected ID, instruction, error and parameters.
//
// Input: [selector][id][a0 a1][b0 b1][c][s0 s1][rest...]; selector bit 7 picks 2.0, its low
// bits the encoder; a = address, b = length (little-endian), c = error / option / instruction;
// s = output buffer bytes (0: the largest, 2 KiB); rest = parameters, records, IDs or 5-byte
// BULK_READ entries [id, address, length].
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "stride/hal/dynamixel/codec_v1.hpp"
#include "stride/hal/dynamixel/codec_v2.hpp"
#include "stride/hal/dynamixel/packet_parser.hpp"

using namespace stride::hal::dxl;

namespace {

using Bytes = std::vector<std::uint8_t>;

struct Expected {
  bool encodable = true;  ///< false: the request itself cannot be encoded
  bool is_status = false;
  bool broadcast = false;  ///< SYNC_* / BULK_READ encoders address the broadcast ID
  std::uint8_t code = 0;   ///< instruction code (status: the error byte in 1.0)
  std::uint8_t error = 0;
  Bytes params;
};

void append(Bytes& to, std::span<const std::uint8_t> bytes) {
  to.insert(to.end(), bytes.begin(), bytes.end());
}
void append_u16(Bytes& to, std::uint16_t v) {
  to.push_back(static_cast<std::uint8_t>(v & 0xFFU));
  to.push_back(static_cast<std::uint8_t>(v >> 8));
}

// Bytes of a 2.0 packet whose instruction + parameter field is `body`, after byte stuffing.
std::size_t v2_size(const Bytes& body) {
  std::size_t stuffed = 0;
  std::uint8_t last[3] = {0, 0, 0};
  std::size_t seen = 0;
  for (const std::uint8_t b : body) {
    ++stuffed;
    last[0] = last[1];
    last[1] = last[2];
    last[2] = b;
    ++seen;
    if (seen >= 3 && last[0] == 0xFF && last[1] == 0xFF && last[2] == 0xFD) {
      ++stuffed;  // the stuffing byte FD
      last[0] = last[1];
      last[1] = last[2];
      last[2] = 0xFD;
    }
  }
  return 7 + stuffed + 2;
}

std::vector<BulkReadEntry> entries_of(std::span<const std::uint8_t> rest) {
  std::vector<BulkReadEntry> entries;
  for (std::size_t k = 0; k + 5 <= rest.size(); k += 5) {
    entries.push_back({rest[k], read_u16(&rest[k + 1]), read_u16(&rest[k + 3])});
  }
  return entries;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 9) return 0;
  const bool v2 = (data[0] & 0x80) != 0;
  const unsigned which = data[0] & 0x7F;
  const std::uint8_t id = data[1];
  const std::uint16_t a = read_u16(data + 2);
  const std::uint16_t b = read_u16(data + 4);
  const std::uint8_t c = data[6];
  const std::span<const std::uint8_t> rest(data + 9, size - 9);
  static std::uint8_t buffer[2 * kMaxPacketBytes];
  const std::size_t cap = read_u16(data + 7) == 0 ? sizeof(buffer) : read_u16(data + 7);
  const std::span<std::uint8_t> out(buffer, cap < sizeof(buffer) ? cap : sizeof(buffer));
  const std::uint8_t a8 = static_cast<std::uint8_t>(a & 0xFFU);
  const std::uint8_t b8 = static_cast<std::uint8_t>(b & 0xFFU);

  Expected e;
  std::size_t n = 0;
  if (!v2) {
    switch (which % 10) {
      case 0:
        n = v1::encode_instruction(out, id, c, rest);
        e.code = c;
        append(e.params, rest);
        break;
      case 1:
        n = v1::encode_status(out, id, c, rest);
        e.is_status = true;
        e.code = instruction::kStatus;
        e.error = c;
        append(e.params, rest);
        break;
      case 2:
        n = v1::encode_ping(out, id);
        e.code = instruction::kPing;
        break;
      case 3:
        n = v1::encode_read(out, id, a8, b8);
        e.code = instruction::kRead;
        e.params = {a8, b8};
        break;
      case 4:
      case 5:
        n = (which % 10 == 4 ? v1::encode_write : v1::encode_reg_write)(out, id, a8, rest);
        e.code = which % 10 == 4 ? instruction::kWrite : instruction::kRegWrite;
        e.params = {a8};
        append(e.params, rest);
        break;
      case 6:
        n = v1::encode_action(out, id);
        e.code = instruction::kAction;
        break;
      case 7:
        n = v1::encode_reset(out, id);
        e.code = instruction::kReset;
        break;
      case 8:
        n = v1::encode_sync_write(out, a8, b8, rest);
        e.code = instruction::kSyncWrite;
        e.broadcast = true;
        e.encodable = b8 != 0 && rest.size() % (b8 + 1U) == 0;
        e.params = {a8, b8};
        append(e.params, rest);
        break;
      default: {
        const auto entries = entries_of(rest);
        n = v1::encode_bulk_read(out, entries);
        e.code = instruction::kBulkRead;
        e.broadcast = true;
        e.params = {0x00};
        for (const BulkReadEntry& x : entries) {
          if (x.length > 0xFF || x.address > 0xFF) e.encodable = false;
          e.params.insert(e.params.end(), {static_cast<std::uint8_t>(x.length), x.id,
                                           static_cast<std::uint8_t>(x.address)});
        }
        break;
      }
    }
    const std::uint8_t wire_id = e.broadcast ? kBroadcastId : id;
    const std::size_t total = v1::packet_size(e.params.size());
    const bool fits = e.encodable && e.params.size() <= 253 && total <= out.size();
    if (n != (fits ? total : 0)) std::abort();
    if (n == 0 || wire_id == 0xFF) return 0;  // ID 0xFF is not a valid packet ID
    PacketParser parser(Protocol::kV1,
                        e.is_status ? PacketParser::Role::kHost : PacketParser::Role::kDevice);
    (void)parser.feed(out.first(n));
    Packet p;
    if (!parser.next(p) || p.id != wire_id || p.is_status != e.is_status ||
        p.instruction != e.code || p.error != e.error ||
        !std::equal(e.params.begin(), e.params.end(), p.params.begin(),
                    p.params.begin() + p.param_count) ||
        p.param_count != e.params.size()) {
      std::abort();
    }
    return 0;
  }

  switch (which % 12) {
    case 0:
      n = v2::encode_instruction(out, id, c, rest);
      e.code = c;
      append(e.params, rest);
      break;
    case 1:
      n = v2::encode_status(out, id, c, rest);
      e.is_status = true;
      e.code = instruction::kStatus;
      e.error = c;
      append(e.params, rest);
      break;
    case 2:
      n = v2::encode_ping(out, id);
      e.code = instruction::kPing;
      break;
    case 3:
      n = v2::encode_read(out, id, a, b);
      e.code = instruction::kRead;
      append_u16(e.params, a);
      append_u16(e.params, b);
      break;
    case 4:
    case 5:
      n = (which % 12 == 4 ? v2::encode_write : v2::encode_reg_write)(out, id, a, rest);
      e.code = which % 12 == 4 ? instruction::kWrite : instruction::kRegWrite;
      append_u16(e.params, a);
      append(e.params, rest);
      break;
    case 6:
      n = v2::encode_action(out, id);
      e.code = instruction::kAction;
      break;
    case 7:
      n = v2::encode_factory_reset(out, id, c);
      e.code = instruction::kReset;
      e.params = {c};
      break;
    case 8:
      n = v2::encode_reboot(out, id);
      e.code = instruction::kReboot;
      break;
    case 9:
      n = v2::encode_sync_read(out, a, b, rest);
      e.code = instruction::kSyncRead;
      e.broadcast = true;
      append_u16(e.params, a);
      append_u16(e.params, b);
      append(e.params, rest);
      break;
    case 10:
      n = v2::encode_sync_write(out, a, b, rest);
      e.code = instruction::kSyncWrite;
      e.broadcast = true;
      e.encodable = b != 0 && rest.size() % (b + 1U) == 0;
      append_u16(e.params, a);
      append_u16(e.params, b);
      append(e.params, rest);
      break;
    default: {
      const auto entries = entries_of(rest);
      n = v2::encode_bulk_read(out, entries);
      e.code = instruction::kBulkRead;
      e.broadcast = true;
      e.encodable = entries.size() * 5 <= kMaxParams;
      for (const BulkReadEntry& x : entries) {
        e.params.push_back(x.id);
        append_u16(e.params, x.address);
        append_u16(e.params, x.length);
      }
      break;
    }
  }
  const std::uint8_t wire_id = e.broadcast ? kBroadcastId : id;
  Bytes body{e.code};
  if (e.is_status) body.push_back(e.error);
  append(body, e.params);
  const std::size_t total = v2_size(body);
  const std::size_t limit = out.size() < kMaxPacketBytes ? out.size() : kMaxPacketBytes;
  const bool fits = e.encodable && out.size() >= 10 && total <= limit;
  if (n != (fits ? total : 0)) std::abort();
  if (n == 0 || wire_id == 0xFD || wire_id == 0xFF) return 0;  // reserved IDs do not parse
  PacketParser parser(Protocol::kV2, PacketParser::Role::kHost);
  (void)parser.feed(out.first(n));
  Packet p;
  if (!e.is_status && e.code == instruction::kStatus) {
    // Instruction byte 0x55 marks a status packet: its first parameter is the error field,
    // and without one the packet is refused.
    if (e.params.empty()) {
      if (parser.next(p)) std::abort();
      return 0;
    }
    e.is_status = true;
    e.error = e.params.front();
    e.params.erase(e.params.begin());
  }
  if (!parser.next(p) || p.id != wire_id || p.is_status != e.is_status || p.instruction != e.code ||
      p.error != e.error || p.param_count != e.params.size() ||
      !std::equal(e.params.begin(), e.params.end(), p.params.begin())) {
    std::abort();
  }
  return 0;
}
