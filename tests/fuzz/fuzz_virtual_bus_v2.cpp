// libFuzzer target: the protocol 2.0 virtual bus (20 MX(2.0) servos: parser in device role,
// register writes and their checks, position limits, FACTORY_RESET options, SYNC/BULK reads
// and writes, fault injection) fed arbitrary host bytes. Its replies must parse, one status
// packet per counted reply, and none damaged unless corruption was injected.
//
// Input: [flags][silent id][overheat id][chunk][host bytes...], as fuzz_virtual_bus (with flag
// 0x10 faults start after the first SYNC_READ or BULK_READ).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "stride/hal/dynamixel/packet_parser.hpp"
#include "stride/hal/dynamixel/virtual_bus_v2.hpp"

using namespace stride::hal::dxl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 4) return 0;
  VirtualBusV2::Options options;
  const std::uint8_t flags = data[0];
  options.lockstep = (flags & 0x20) == 0;
  if ((flags & 0x40) != 0) {
    for (std::size_t i = 1; i < options.calibration.size(); i += 2)
      options.calibration[i].model = ServoModelId::kMx64;
  }
  // The `--fault` items of `stride vbus` (IDs above 253 are refused and leave no fault).
  if ((flags & 0x01) != 0) (void)options.faults.add("drop:0.3");
  if ((flags & 0x02) != 0) (void)options.faults.add("corrupt:0.3");
  if ((flags & 0x04) != 0) (void)options.faults.add("silent:" + std::to_string(data[1]));
  if ((flags & 0x08) != 0) (void)options.faults.add("overheat:" + std::to_string(data[2]));
  if ((flags & 0x10) != 0) (void)options.faults.add("start:1");
  FirstOrderPhysics::Options physics;
  for (std::size_t i = 0; i < options.calibration.size(); ++i)
    physics.models[i] = options.calibration[i].model;
  VirtualBusV2 bus(options, std::make_unique<FirstOrderPhysics>(physics));

  std::vector<std::uint8_t> out;
  std::int64_t delay = 0;
  const std::size_t chunk = data[3] == 0 ? size : data[3];
  for (std::size_t offset = 4; offset < size; offset += chunk) {
    const std::size_t n = chunk < size - offset ? chunk : size - offset;
    bus.receive({data + offset, n}, out, delay);
  }
  PacketParser parser(Protocol::kV2, PacketParser::Role::kHost);
  std::size_t offset = 0;
  Packet p;
  while (offset < out.size()) {
    offset += parser.feed({out.data() + offset, out.size() - offset});
    while (parser.next(p)) {
      if (!p.is_status) std::abort();  // the servos send status packets only
    }
  }
  const VirtualBusCounters& c = bus.counters();
  if (c.corrupted == 0 && (parser.stats().bad_checksum != 0 || parser.stats().packets != c.replies))
    std::abort();
  if (c.error_replies > c.replies) std::abort();
  // No device can take ID 254 (IDs go up to 253), so peek finds none there.
  if (bus.peek(254, data[2], 1) != 0) std::abort();
  (void)bus.peek(data[1], data[2], 4);
  return 0;
}
