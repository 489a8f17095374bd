// libFuzzer target: the virtual buses' instruction handling (1.0 and 2.0: parser in device
// role, register writes, SYNC_WRITE/SYNC_READ/BULK_READ decoding) fed arbitrary host bytes.
// Their replies must parse without a checksum/CRC error.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <vector>

#include "stride/hal/dynamixel/packet_parser.hpp"
#include "stride/hal/dynamixel/virtual_bus.hpp"
#include "stride/hal/dynamixel/virtual_bus_v2.hpp"

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

  VirtualBusV2::Options options2;
  options2.lockstep = true;
  VirtualBusV2 bus2(options2, std::make_unique<FirstOrderPhysics>(physics));
  out.clear();
  bus2.receive({data, size}, out, delay);
  PacketParser parser2(Protocol::kV2, PacketParser::Role::kHost);
  offset = 0;
  while (offset < out.size()) {
    offset += parser2.feed({out.data() + offset, out.size() - offset});
    while (parser2.next(p)) {
    }
  }
  if (parser2.stats().bad_checksum != 0) std::abort();
  return 0;
}
