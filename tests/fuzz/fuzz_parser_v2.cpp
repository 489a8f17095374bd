// libFuzzer target: the protocol 2.0 streaming parser (CRC-16, byte stuffing), fed the input in
// chunks whose sizes come from the input. Every packet handed out must re-encode (with
// stuffing) to a packet that parses back to the same content.
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
      std::memcmp(q.params.data(), p.params.data(), p.param_count) != 0) {
    std::abort();
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = 1 + data[0] % 61;
  PacketParser parser(Protocol::kV2, PacketParser::Role::kHost);
  Packet p;
  std::size_t offset = 1;
  while (offset < size) {
    const std::size_t n = chunk < size - offset ? chunk : size - offset;
    std::size_t taken = 0;
    while (taken < n) {
      taken += parser.feed({data + offset + taken, n - taken});
      while (parser.next(p)) check(p);
    }
    offset += n;
  }
  while (parser.skip_incomplete()) {
    while (parser.next(p)) check(p);
  }
  return 0;
}
