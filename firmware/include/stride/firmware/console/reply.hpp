// Reply: what the console answers to one command line, and the error codes it uses.
//
// Wire format (firmware/console/README.md): zero or more data lines, then exactly one final
// line, either `ok` or `ok <text>`, or `err <code> <message>`. Data lines never start with the
// word "ok" or "err". On a serial line or pty every line ends with CR LF and the final line is
// followed by the prompt "> " (no line end); on stdio lines end with LF and there is no prompt.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace stride::fw::console {

/// Error codes of `err <code> <message>` (stable: programs match on them).
enum class ErrorCode {
  kUsage,             ///< wrong number or form of arguments
  kUnknownCommand,    ///< the first word is not a command
  kUnknownParameter,  ///< no parameter of that name
  kBadValue,          ///< not a number/bool, wrong type or outside the bounds
  kReadOnly,          ///< the parameter cannot be written
  kRefused,           ///< the safety rules forbid it now (the message says why)
  kBadFile,           ///< a parameter file (load/flash) is malformed or invalid: nothing applied
  kIo,                ///< a file could not be read or written
  kLineTooLong,       ///< the line exceeded the console's line limit and was discarded
};

std::string_view to_string(ErrorCode code);

struct Reply {
  std::vector<std::string> data;  ///< data lines (without line ends)
  std::string final_line;         ///< "ok ..." or "err <code> <message>"

  bool ok() const { return final_line.rfind("ok", 0) == 0; }

  static Reply success(std::string text = {}) {
    Reply r;
    r.final_line = text.empty() ? "ok" : "ok " + text;
    return r;
  }
  static Reply error(ErrorCode code, std::string_view message) {
    Reply r;
    r.final_line = "err " + std::string(to_string(code)) + " " + std::string(message);
    return r;
  }
};

}  // namespace stride::fw::console
