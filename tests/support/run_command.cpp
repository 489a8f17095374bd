// run_command: popen() wrapper for command-line tests.
#include "run_command.hpp"

#include <sys/wait.h>

#include <cstdio>

namespace stride::test {

std::string run_command(const std::string& command, int& code) {
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (pipe != nullptr && fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = pipe != nullptr ? pclose(pipe) : -1;
  code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

}  // namespace stride::test
