// How a `stride` subcommand reports what went wrong (the contract in command.hpp): one line
// "stride COMMAND: message" on stderr, then exit 2 for bad input or 1 for a failure while
// running. Each command file holds one CommandErrors named after its command.
#pragma once

#include <string>

namespace stride::tools {

inline constexpr int kExitBadInput = 2;  ///< bad input: an option, argument or input file
inline constexpr int kExitFailure = 1;   ///< the command started and failed

class CommandErrors {
 public:
  /// `command` is the name after "stride " ("sim", "sim servo"); it must outlive this object.
  explicit constexpr CommandErrors(const char* command) : command_(command) {}

  /// Prints "stride COMMAND: message" and returns kExitBadInput.
  int bad_input(const std::string& message) const;
  /// Prints "stride COMMAND: message" and returns kExitFailure.
  int failure(const std::string& message) const;
  /// Prints "stride COMMAND: warning: message" (the command goes on).
  void warning(const std::string& message) const;

 private:
  const char* command_;
};

}  // namespace stride::tools
