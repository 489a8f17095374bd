// VirtualBusStream: an in-process ByteStream connected to an emulated bus (VirtualBus,
// VirtualBusV2), for tests and benches. write() hands the bytes to the bus at once; its replies are
// queued for read_some(), which never waits (nothing else can arrive in-process), so a missing
// reply is a timeout at once.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "stride/hal/dynamixel/bus_responder.hpp"
#include "stride/hal/dynamixel/byte_stream.hpp"

namespace stride::hal::dxl {

class VirtualBusStream final : public ByteStream {
 public:
  VirtualBusStream(BusResponder& bus, std::uint32_t baud) : bus_(bus), baud_(baud) {
    pending_.reserve(4096);
  }
  bool write(std::span<const std::uint8_t> bytes, std::int64_t) noexcept override {
    std::int64_t delay_us = 0;
    bus_.receive(bytes, pending_, delay_us);
    return true;
  }
  std::ptrdiff_t read_some(std::span<std::uint8_t> out, std::int64_t) noexcept override {
    const std::size_t n = std::min(out.size(), pending_.size() - read_pos_);
    for (std::size_t k = 0; k < n; ++k) out[k] = pending_[read_pos_ + k];
    read_pos_ += n;
    if (read_pos_ == pending_.size()) {
      pending_.clear();
      read_pos_ = 0;
    }
    return static_cast<std::ptrdiff_t>(n);
  }
  void discard_input() noexcept override {
    pending_.clear();
    read_pos_ = 0;
  }
  std::uint32_t baud() const noexcept override { return baud_; }

 private:
  BusResponder& bus_;
  std::uint32_t baud_;
  std::vector<std::uint8_t> pending_;
  std::size_t read_pos_ = 0;
};

}  // namespace stride::hal::dxl
