// SerialPort: a Dynamixel bus line on a serial device (USB2Dynamixel, the CM730's FTDI) or a
// pseudo-terminal (the virtual bus), opened exclusively, 8N1 raw, no flow control.
//
// Real devices are opened and configured through libserialport. libserialport 0.1.1 cannot
// describe Linux pseudo-terminals (sp_get_port_by_name looks the device up in /sys/class/tty,
// where ptys are absent), so a pty is opened with POSIX termios instead; reading and writing
// are the same for both (poll() on the descriptor with a nanosecond deadline: no busy waiting).
//
// Low latency: a USB-serial adapter's latency timer (/sys/bus/usb-serial/devices/<tty>/
// latency_timer, default 16 ms) is set to 1 ms when the device has one and it is writable;
// otherwise (pty, built-in UART, no permission) this is skipped quietly and reported by
// latency_timer_set(). Exclusive: TIOCEXCL plus an flock, so a second opener fails.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "stride/core/status.hpp"
#include "stride/hal/dynamixel/byte_stream.hpp"

struct sp_port;

namespace stride::hal::dxl {

class SerialPort final : public ByteStream {
 public:
  /// Standard rates accepted (Dynamixel 1.0/2.0 and common UART rates).
  static bool is_standard_baud(std::uint32_t baud);

  /// Opens `path` at `baud`. The error names the device and the reason.
  static Status open(const std::string& path, std::uint32_t baud, std::unique_ptr<SerialPort>& out);
  ~SerialPort() override;
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  bool write(std::span<const std::uint8_t> bytes, std::int64_t deadline_ns) noexcept override;
  std::ptrdiff_t read_some(std::span<std::uint8_t> out, std::int64_t deadline_ns) noexcept override;
  void discard_input() noexcept override;
  std::uint32_t baud() const noexcept override { return baud_; }

  const std::string& path() const { return path_; }
  bool is_pseudo_terminal() const { return pty_; }
  bool latency_timer_set() const { return latency_timer_set_; }

 private:
  SerialPort() = default;
  std::string path_;
  std::uint32_t baud_ = 0;
  sp_port* port_ = nullptr;  ///< libserialport handle (real devices)
  int fd_ = -1;              ///< descriptor used for I/O (owned when port_ is null)
  bool pty_ = false;
  bool latency_timer_set_ = false;
};

}  // namespace stride::hal::dxl
