// BenchV2: the protocol 2.0 virtual bus (20 MX(2.0) servos, lockstep, servo 13 overheating)
// driven in-process with packets built by the 2.0 codec or written out byte by byte.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "dxl_test_util.hpp"
#include "stride/firmware/dynamixel_config.hpp"
#include "stride/hal/dynamixel/codec_v2.hpp"
#include "stride/hal/dynamixel/virtual_bus_v2.hpp"

namespace stride::hal::dxl::test {

struct BenchV2 {
  explicit BenchV2(VirtualBusV2::Options options = {}) {
    options.calibration = fw::servo_calibrations(fw::ServoTable::defaults());
    options.lockstep = true;
    options.faults.overheat[13] = true;
    FirstOrderPhysics::Options physics;
    for (std::size_t i = 0; i < kServoCount; ++i) physics.models[i] = options.calibration[i].model;
    bus = std::make_unique<VirtualBusV2>(options, std::make_unique<FirstOrderPhysics>(physics));
  }
  template <typename F>
  std::vector<Packet> call(F encode) {
    Bytes b(1100);
    b.resize(encode(std::span<std::uint8_t>(b)));
    return send(b);
  }
  std::vector<Packet> send(const Bytes& b) {
    return parse_all(Protocol::kV2, PacketParser::Role::kHost, raw(b));
  }
  /// The bytes the bus sends back.
  Bytes raw(const Bytes& b) {
    std::vector<std::uint8_t> out;
    std::int64_t delay = 0;
    bus->receive(b, out, delay);
    return out;
  }
  std::unique_ptr<VirtualBusV2> bus;
};

}  // namespace stride::hal::dxl::test
