// BusResponder: the device side of a byte-stream Dynamixel bus (the emulated buses
// VirtualBus (1.0) and VirtualBusV2 (2.0)), served in-process or on a pseudo-terminal.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace stride::hal::dxl {

class BusResponder {
 public:
  virtual ~BusResponder() = default;
  /// Consumes bytes from the host and appends the devices' replies to `out`; adds the
  /// replies' summed return delay time [us] to `reply_delay_us`.
  virtual void receive(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out,
                       std::int64_t& reply_delay_us) = 0;
};

}  // namespace stride::hal::dxl
