// ConsoleServer: the parameter console's thread. Reads bytes from a transport, edits them into
// lines (line_editor.hpp), executes each line (command_interpreter.hpp) and writes the reply
// and a "> " prompt back. It runs at normal (SCHED_OTHER) priority even when started from a
// SCHED_FIFO thread, and only talks to the control loop through the ParameterStore's staging
// area and the Controller's request mailbox, which never block the control thread.
//
// Link loss: when the transport reports the link down, the server closes it and reopens it
// with exponential back-off (50 ms doubling to 2 s, reset after a successful open); it sleeps
// at least the back-off between a loss and the next open, so a link that keeps dropping never
// makes it spin. stdio at EOF ends the console (the loop carries on).
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "stride/firmware/console/command_interpreter.hpp"
#include "stride/firmware/console/line_editor.hpp"
#include "stride/firmware/console/transport.hpp"

namespace stride::fw::console {

struct ServerCounters {
  std::atomic<std::uint64_t> lines{0};           ///< command lines executed
  std::atomic<std::uint64_t> errors{0};          ///< replies that were `err`
  std::atomic<std::uint64_t> overlong_lines{0};  ///< lines discarded for length
  std::atomic<std::uint64_t> noise_bytes{0};     ///< bytes dropped as binary noise
  std::atomic<std::uint64_t> opens{0};           ///< successful (re)opens of the link
  std::atomic<std::uint64_t> link_losses{0};     ///< times the link went down
  std::atomic<std::uint64_t> failed_opens{0};    ///< open attempts that failed
};

struct ServerOptions {
  std::size_t max_line = LineEditor::kDefaultMaxLine;
  std::chrono::milliseconds min_backoff{50};
  std::chrono::milliseconds max_backoff{2000};
  bool banner = true;  ///< greet with a one-line banner on every (re)open of a serial link
};

class ConsoleServer {
 public:
  ConsoleServer(std::unique_ptr<ConsoleTransport> transport, ConsoleContext context,
                ServerOptions options = {});
  ~ConsoleServer();
  ConsoleServer(const ConsoleServer&) = delete;
  ConsoleServer& operator=(const ConsoleServer&) = delete;

  /// Starts the console thread (once).
  void start();
  /// Asks the thread to finish and joins it (within about 100 ms, or the transport's write
  /// timeout if a write is blocked).
  void stop();
  /// True once the thread has ended by itself (stdio at EOF).
  bool finished() const noexcept { return finished_.load(); }

  const ServerCounters& counters() const noexcept { return counters_; }

 private:
  void run();
  void serve_bytes(std::string_view bytes);
  void sleep_interruptible(std::chrono::milliseconds duration);

  std::unique_ptr<ConsoleTransport> transport_;
  CommandInterpreter interpreter_;
  LineEditor editor_;
  ServerOptions options_;
  std::string prompt_;    ///< "> " on terminals (serial, pty), none on stdio
  std::string line_end_;  ///< CR LF on terminals, LF on stdio
  ServerCounters counters_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> finished_{false};
  std::thread thread_;
};

/// Builds a console on `where` ("stdio", or a serial device / pty path).
std::unique_ptr<ConsoleServer> make_console(const std::string& where, ConsoleContext context,
                                            ServerOptions options = {});

}  // namespace stride::fw::console
