// ConsoleTransport: the byte link the console talks over (stdio, or a serial device or
// pseudo-terminal through libserialport). Small on purpose: open, read with a timeout, write.
//
// A serial transport can be reopened: when the device disappears or the peer closes it, read()
// reports the link as down, the server closes it and calls open() again with back-off.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

#include "stride/core/status.hpp"

namespace stride::fw::console {

class ConsoleTransport {
 public:
  virtual ~ConsoleTransport() = default;

  /// Opens (or reopens) the link. The error names the device and the reason.
  virtual Status open() = 0;
  virtual void close() = 0;
  virtual bool is_open() const = 0;
  /// Waits up to timeout_ms for input and reads what is there (at most `capacity` bytes).
  /// Returns the byte count, 0 on timeout, -1 when the link is down (closed, vanished, EOF).
  virtual long read(char* buffer, std::size_t capacity, int timeout_ms) = 0;
  /// Writes all bytes (blocking up to about a second); false if the link failed.
  virtual bool write(std::string_view bytes) = 0;
  /// False for links that cannot come back once down (stdio at EOF).
  virtual bool reopenable() const = 0;
  /// Whether the console should echo typed characters (a raw serial terminal expects it;
  /// stdio does not).
  virtual bool wants_echo() const = 0;
  virtual std::string name() const = 0;
};

/// Standard input and output of the process.
std::unique_ptr<ConsoleTransport> make_stdio_transport();

/// A serial device or pseudo-terminal opened with libserialport: 8N1, no flow control, raw,
/// exclusive (TIOCEXCL and an flock, so a second stride-fw or a picocom cannot share it).
/// Options a pseudo-terminal cannot set (baud rate, flow control) are tolerated (tty_port.hpp).
std::unique_ptr<ConsoleTransport> make_serial_transport(std::string device, int baud = 115200);

}  // namespace stride::fw::console
