// TtyPort: a serial device or pseudo-terminal opened for the console, raw 8N1 without flow
// control, exclusive, non-blocking, with poll()-based reads and writes.
//
// Real serial devices are opened and configured through libserialport. libserialport 0.1.1
// cannot describe Linux pseudo-terminals (sp_get_port_by_name looks the device up in
// /sys/class/tty, where ptys are absent), so when it does not know a character device, the
// device is opened with POSIX termios instead; settings a pty refuses are ignored.
// Exclusive: an flock (which picocom and stride honour) plus TIOCEXCL.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "stride/core/status.hpp"

struct sp_port;

namespace stride::fw::console {

class TtyPort {
 public:
  TtyPort() = default;
  ~TtyPort() { close(); }
  TtyPort(const TtyPort&) = delete;
  TtyPort& operator=(const TtyPort&) = delete;

  /// Opens `path` (symlinks followed). The error names the device and the reason.
  Status open(const std::string& path, int baud);
  void close();
  bool is_open() const noexcept { return fd_ >= 0; }

  /// Waits up to timeout_ms for input, then reads what is there. Returns the byte count, 0 on
  /// timeout, -1 when the line is down (hang-up, device gone, EOF, error).
  long read(char* buffer, std::size_t capacity, int timeout_ms);
  /// Writes all bytes within timeout_ms; false on error or timeout.
  bool write(std::string_view bytes, int timeout_ms);
  /// Discards input not read yet.
  void discard_input();

 private:
  sp_port* port_ = nullptr;
  int fd_ = -1;
};

}  // namespace stride::fw::console
