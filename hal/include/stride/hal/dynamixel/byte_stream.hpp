// ByteStream: the byte transport a Dynamixel bus master talks through. Implemented by
// SerialPort (a real serial device or a pseudo-terminal) and by the in-process virtual bus
// (tests). Times are CLOCK_MONOTONIC nanoseconds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace stride::hal::dxl {

/// CLOCK_MONOTONIC now [ns].
std::int64_t monotonic_ns() noexcept;

class ByteStream {
 public:
  virtual ~ByteStream() = default;
  /// Writes every byte or fails; gives up at `deadline_ns`. Returns false on failure/timeout.
  virtual bool write(std::span<const std::uint8_t> bytes, std::int64_t deadline_ns) noexcept = 0;
  /// Blocks (without spinning) until at least one byte is available or `deadline_ns` passes,
  /// then reads what is available into `out`. Returns the count (0 on timeout), -1 on error.
  virtual std::ptrdiff_t read_some(std::span<std::uint8_t> out,
                                   std::int64_t deadline_ns) noexcept = 0;
  /// Drops bytes received but not read yet.
  virtual void discard_input() noexcept = 0;
  /// Line rate [bit/s] used for timing (the configured baud, whether or not the line honours it).
  virtual std::uint32_t baud() const noexcept = 0;
};

/// Time [ns] that `bytes` take on a UART line at `baud` (10 bits per byte: start, 8, stop).
constexpr std::int64_t wire_time_ns(std::size_t bytes, std::uint32_t baud) {
  return baud == 0 ? 0
                   : static_cast<std::int64_t>(bytes) * 10 * 1'000'000'000LL /
                         static_cast<std::int64_t>(baud);
}

}  // namespace stride::hal::dxl
