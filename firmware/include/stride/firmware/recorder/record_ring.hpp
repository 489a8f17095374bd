// RecordRing: a fixed-capacity single-producer single-consumer ring of variable-length
// records (a u32 length, then the bytes), allocated once at construction. The producer (the
// control thread) never blocks and never allocates: a record that does not fit is refused
// whole. The consumer (the recorder's writer thread) takes records out in order.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace stride::fw::flight_log {

class RecordRing {
 public:
  /// Allocates `capacity_bytes` (rounded up to a multiple of 8, at least 64).
  explicit RecordRing(std::size_t capacity_bytes);
  RecordRing(const RecordRing&) = delete;
  RecordRing& operator=(const RecordRing&) = delete;

  /// Producer: appends one record, or returns false (and changes nothing) when the free
  /// space is less than 4 + size bytes. Real-time: lock-free, no allocation.
  bool try_push(const std::uint8_t* data, std::uint32_t size) noexcept;

  /// Consumer: appends the oldest record's bytes to `out` (after clearing it) and returns
  /// true, or returns false when the ring is empty.
  bool try_pop(std::vector<std::uint8_t>& out);

  std::size_t capacity() const noexcept { return capacity_; }
  /// Bytes in use (approximate while the other side runs).
  std::size_t used() const noexcept;

 private:
  void copy_in(std::uint64_t position, const std::uint8_t* data, std::size_t size) noexcept;
  void copy_out(std::uint64_t position, std::uint8_t* data, std::size_t size) const noexcept;

  std::size_t capacity_;
  std::unique_ptr<std::uint8_t[]> bytes_;
  // Monotonic byte positions; position % capacity_ is the index. Written by one side each.
  alignas(64) std::atomic<std::uint64_t> head_{0};  ///< producer: end of the last record
  alignas(64) std::atomic<std::uint64_t> tail_{0};  ///< consumer: start of the oldest record
};

}  // namespace stride::fw::flight_log
