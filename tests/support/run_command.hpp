// run_command: runs a shell command line, returns its standard output and its exit code.
#pragma once

#include <string>

namespace stride::test {

/// Runs `command` through the shell; `code` gets the exit status (-1 if it did not exit).
std::string run_command(const std::string& command, int& code);

}  // namespace stride::test
