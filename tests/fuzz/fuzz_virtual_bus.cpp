// libFuzzer target: the virtual bus's instruction handling (parser in device role, register
// writes, SYNC_WRITE/BULK_READ decoding) fed arbitrary host bytes. Replies must parse.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <vector>

#include "stride/hal/dynamixel/packet_parser.hpp"
#include "stride/hal/dynamixel/virtual_bus.hpp"

using namespace stride::hal::dxl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  VirtualBus::Options options;
  options.lockstep = true;
  FirstOrderPhysics::Options physics;
  VirtualBus bus(options, std::make_unique<FirstOrderPhysics>(physics));
  std::vector<std::uint8_t> out;
  std::int64_t delay = 0;
  bus.receive({data, size}, out, delay);
  PacketParser parser(Protocol::kV1, PacketParser::Role::kHost);
  std::size_t offset = 0;
  Packet p;
  while (offset < out.size()) {
    offset += parser.feed({out.data() + offset, out.size() - offset});
    while (parser.next(p)) {
    }
  }
  if (parser.stats().bad_checksum != 0) std::abort();  // the bus only sends valid packets
  return 0;
}
