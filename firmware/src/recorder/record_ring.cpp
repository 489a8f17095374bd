// RecordRing implementation: acquire/release on the two positions, copies that wrap.
#include "stride/firmware/recorder/record_ring.hpp"

#include <algorithm>
#include <cstring>

#include "stride/firmware/recorder/flight_log_format.hpp"

namespace stride::fw::flight_log {

RecordRing::RecordRing(std::size_t capacity_bytes)
    : capacity_(std::max<std::size_t>(64, (capacity_bytes + 7) / 8 * 8)),
      bytes_(new std::uint8_t[capacity_]()) {}

std::size_t RecordRing::used() const noexcept {
  return static_cast<std::size_t>(head_.load(std::memory_order_acquire) -
                                  tail_.load(std::memory_order_acquire));
}

void RecordRing::copy_in(std::uint64_t position, const std::uint8_t* data,
                         std::size_t size) noexcept {
  const std::size_t at = static_cast<std::size_t>(position % capacity_);
  const std::size_t first = std::min(size, capacity_ - at);
  std::memcpy(bytes_.get() + at, data, first);
  std::memcpy(bytes_.get(), data + first, size - first);
}

void RecordRing::copy_out(std::uint64_t position, std::uint8_t* data,
                          std::size_t size) const noexcept {
  const std::size_t at = static_cast<std::size_t>(position % capacity_);
  const std::size_t first = std::min(size, capacity_ - at);
  std::memcpy(data, bytes_.get() + at, first);
  std::memcpy(data + first, bytes_.get(), size - first);
}

bool RecordRing::try_push(const std::uint8_t* data, std::uint32_t size) noexcept {
  const std::uint64_t head = head_.load(std::memory_order_relaxed);
  const std::uint64_t tail = tail_.load(std::memory_order_acquire);
  const std::size_t needed = 4 + static_cast<std::size_t>(size);
  if (capacity_ - static_cast<std::size_t>(head - tail) < needed) return false;
  std::uint8_t length[4];
  put_u32(length, size);
  copy_in(head, length, 4);
  copy_in(head + 4, data, size);
  head_.store(head + needed, std::memory_order_release);
  return true;
}

bool RecordRing::try_pop(std::vector<std::uint8_t>& out) {
  const std::uint64_t tail = tail_.load(std::memory_order_relaxed);
  const std::uint64_t head = head_.load(std::memory_order_acquire);
  if (head == tail) return false;
  std::uint8_t length[4];
  copy_out(tail, length, 4);
  const std::uint32_t size = get_u32(length);
  out.resize(size);
  copy_out(tail + 4, out.data(), size);
  tail_.store(tail + 4 + size, std::memory_order_release);
  return true;
}

}  // namespace stride::fw::flight_log
