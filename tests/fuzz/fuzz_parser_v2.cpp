// libFuzzer target: the protocol 2.0 streaming parser (CRC-16, byte stuffing), fed the input in
// chunks as a serial port delivers them. Every packet handed out must re-encode (with stuffing)
// to a packet that parses back to the same content.
//
// Input: [control][bytes...]. Chunk size = 1 + (control & 0x7F) % 61. Control bit 7 = lazy:
// packets are taken out only when the parser's buffer takes no more bytes and at the end.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "stride/hal/dynamixel/codec_v2.hpp"
#include "stride/hal/dynamixel/packet_parser.hpp"

using namespace stride::hal::dxl;

namespace {
void check(const Packet& p) {
  static std::uint8_t again[2 * kMaxPacketBytes];
  const std::size_t n = p.is_status
                            ? v2::encode_status(again, p.id, p.error, p.parameters())
                            : v2::encode_instruction(again, p.id, p.instruction, p.parameters());
  if (n == 0) return;  // re-stuffing can make a maximal packet too long to build: allowed
  PacketParser back(Protocol::kV2, PacketParser::Role::kHost);
  (void)back.feed({again, n});
  Packet q;
  if (!back.next(q) || q.param_count != p.param_count || q.id != p.id ||
      q.instruction != p.instruction || q.error != p.error || q.is_status != p.is_status ||
      std::memcmp(q.params.data(), p.params.data(), p.param_count) != 0) {
    std::abort();
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = 1 + (data[0] & 0x7FU) % 61;
  const bool lazy = (data[0] & 0x80U) != 0;
  PacketParser parser(Protocol::kV2, PacketParser::Role::kHost);
  Packet p;
  std::uint64_t handed_out = 0;
  std::size_t offset = 1;
  while (offset < size) {
    const std::size_t n = chunk < size - offset ? chunk : size - offset;
    std::size_t taken = 0;
    while (taken < n) {
      const std::size_t t = parser.feed({data + offset + taken, n - taken});
      taken += t;
      if (lazy && taken == n) break;
      if (lazy && t > 0) continue;  // feed until the buffer takes nothing more, then drain
      while (parser.next(p)) {
        check(p);
        ++handed_out;
      }
    }
    offset += n;
  }
  for (;;) {
    while (parser.next(p)) {
      check(p);
      ++handed_out;
    }
    if (!parser.skip_incomplete()) break;
  }
  if (parser.buffered() != 0 || parser.stats().packets != handed_out) std::abort();
  return 0;
}
