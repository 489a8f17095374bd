// PseudoTerminal: a pty for tests of serial programs. The test keeps the master side; the
// program under test opens slave_path() (or a symlink to it) as if it were a serial port.
// Also PtyBridge: two ptys whose masters are relayed to each other by a thread (what
// `socat pty pty` does), so that two programs can talk over two serial-port paths.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <thread>

namespace stride::test {

class PseudoTerminal {
 public:
  PseudoTerminal();  ///< opens a master (throws std::runtime_error if the OS refuses)
  ~PseudoTerminal();
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  const std::string& slave_path() const { return slave_path_; }
  int master_fd() const { return master_; }

  /// Writes all bytes to the master (waits while the line is full, up to 5 s).
  bool write(std::string_view bytes);
  /// Reads what arrives within `timeout` and appends it to `out`; returns false on hang-up.
  bool read_for(std::string& out, std::chrono::milliseconds timeout);
  /// Reads until `done(received)` holds or `timeout` passes; returns whether it held.
  bool read_until(std::string& received, const std::function<bool(const std::string&)>& done,
                  std::chrono::milliseconds timeout);
  /// Sends `line` + CR and returns everything up to and including the reply's final line
  /// (`ok...` or `err ...` at the start of a line), or "" on timeout.
  std::string command(std::string_view line,
                      std::chrono::milliseconds timeout = std::chrono::seconds(5));
  /// Closes the master (the slave side sees a hang-up).
  void close_master();

 private:
  int master_ = -1;
  std::string slave_path_;
};

/// The final line of a reply in `text` (the last line starting with "ok" or "err "), or "".
std::string final_line_of(const std::string& text);

class PtyBridge {
 public:
  PtyBridge();
  ~PtyBridge();
  const std::string& a() const { return a_.slave_path(); }
  const std::string& b() const { return b_.slave_path(); }

 private:
  PseudoTerminal a_, b_;
  std::atomic<bool> stop_{false};
  std::thread relay_;
};

}  // namespace stride::test
