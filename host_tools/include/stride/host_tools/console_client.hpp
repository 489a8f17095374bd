// ConsoleClient: the host side of the parameter console protocol (firmware/console/README.md).
// Opens a serial device or pseudo-terminal (stride::fw::console::TtyPort), sends one command line
// at a time and collects the reply: the console's echo of the line and its "> " prompts are
// skipped, data lines are kept, and the reply ends at the final `ok ...` / `err ...` line.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "stride/core/status.hpp"
#include "stride/firmware/console/tty_port.hpp"

namespace stride::tools {

struct ConsoleReply {
  std::vector<std::string> data;  ///< data lines
  std::string final_line;         ///< "ok ..." or "err <code> <message>"
  bool ok() const { return final_line == "ok" || final_line.rfind("ok ", 0) == 0; }
};

class ConsoleClient {
 public:
  ConsoleClient() = default;
  ConsoleClient(const ConsoleClient&) = delete;
  ConsoleClient& operator=(const ConsoleClient&) = delete;

  /// Opens the port (raw 8N1, exclusive; settings a pty refuses are ignored), abandons any
  /// half-typed line on the console (Ctrl-C) and discards what the console sent before.
  Status open(const std::string& port, int baud = 115200);
  /// Sends `line` and waits up to timeout_ms for the final line of its reply. The error says
  /// whether the port failed or the console did not answer in time.
  Status command(const std::string& line, ConsoleReply& out, int timeout_ms = 5000);

 private:
  Status read_line(std::string& line, long long deadline_ms);
  void drain(int quiet_ms);

  fw::console::TtyPort port_;
  std::string pending_;  ///< bytes received but not yet split into lines
};

/// True if `line` (prompt already removed) ends a reply: "ok", "ok ..." or "err ...".
bool is_final_line(const std::string& line);

/// flash --verify: does the value the console printed (`get`: "0.85", "true", "12") equal the
/// file's value? Numbers match within 1e-9 relative; bools by name; anything else never.
bool value_matches(const nlohmann::json& expected, const std::string& robot_text);

}  // namespace stride::tools
