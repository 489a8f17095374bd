// CommandErrors (command_errors.hpp): the one-line messages and exit codes of every subcommand.
#include "stride/host_tools/command_errors.hpp"

#include <cstdio>

namespace stride::tools {

int CommandErrors::bad_input(const std::string& message) const {
  std::fprintf(stderr, "stride %s: %s\n", command_, message.c_str());
  return kExitBadInput;
}

int CommandErrors::failure(const std::string& message) const {
  std::fprintf(stderr, "stride %s: %s\n", command_, message.c_str());
  return kExitFailure;
}

void CommandErrors::warning(const std::string& message) const {
  std::fprintf(stderr, "stride %s: warning: %s\n", command_, message.c_str());
}

}  // namespace stride::tools
