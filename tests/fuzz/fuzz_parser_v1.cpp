// libFuzzer target: the protocol 1.0 streaming parser (host and device roles), fed the input in
// chunks whose sizes come from the input itself. Every packet handed out must re-encode to a
// packet that parses back to the same content.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "stride/hal/dynamixel/codec_v1.hpp"
#include "stride/hal/dynamixel/packet_parser.hpp"

using namespace stride::hal::dxl;

namespace {
void check(const Packet& p, bool host) {
  std::uint8_t again[300];
  const std::size_t n = host ? v1::encode_status(again, p.id, p.error, p.parameters())
                             : v1::encode_instruction(again, p.id, p.instruction, p.parameters());
  if (n == 0) std::abort();
  PacketParser back(Protocol::kV1, host ? PacketParser::Role::kHost : PacketParser::Role::kDevice);
  (void)back.feed({again, n});
  Packet q;
  if (!back.next(q) || q.param_count != p.param_count || q.id != p.id) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = 1 + data[0] % 37;
  for (const bool host : {true, false}) {
    PacketParser parser(Protocol::kV1,
                        host ? PacketParser::Role::kHost : PacketParser::Role::kDevice);
    Packet p;
    std::size_t offset = 1;
    while (offset < size) {
      const std::size_t n = chunk < size - offset ? chunk : size - offset;
      std::size_t taken = 0;
      while (taken < n) {
        taken += parser.feed({data + offset + taken, n - taken});
        while (parser.next(p)) check(p, host);
      }
      offset += n;
    }
    while (parser.skip_incomplete()) {
      while (parser.next(p)) check(p, host);
    }
  }
  return 0;
}
