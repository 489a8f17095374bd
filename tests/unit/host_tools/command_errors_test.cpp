// CommandErrors (command_errors.hpp): one line "stride COMMAND: message" on stderr, exit 2 for bad
// input and 1 for a failure; a warning says so and returns nothing. run_command (command.hpp)
// turns an exception that escapes a command into the same failure line.
#include <new>
#include <stdexcept>

#include <gtest/gtest.h>

#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"

namespace stride::tools {
namespace {

TEST(CommandErrors, PrintOneLineNamingTheCommandAndReturnTheExitCode) {
  const CommandErrors errors("sim servo");
  testing::internal::CaptureStderr();
  EXPECT_EQ(errors.bad_input("--model: unknown model 'mx28'"), 2);
  EXPECT_EQ(errors.failure("episode ended: NaN"), 1);
  errors.warning("mlockall refused (Operation not permitted)");
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "stride sim servo: --model: unknown model 'mx28'\n"
            "stride sim servo: episode ended: NaN\n"
            "stride sim servo: warning: mlockall refused (Operation not permitted)\n");
}

int throws_runtime_error(int, char**) {
  throw std::runtime_error("json.exception.type_error.302: type must be number");
}
int throws_bad_alloc(int, char**) {
  throw std::bad_alloc();
}
int throws_an_int(int, char**) {
  throw 42;
}
int returns_bad_input(int argc, char**) {
  return argc == 1 ? kExitBadInput : 0;
}

TEST(RunCommand, AnEscapedExceptionIsOneFailureLineAndExitOne) {
  char name[] = "report";
  char* argv[] = {name, nullptr};
  testing::internal::CaptureStderr();
  EXPECT_EQ(run_command({"report", "", throws_runtime_error}, 1, argv), kExitFailure);
  EXPECT_EQ(run_command({"sim", "", throws_bad_alloc}, 1, argv), kExitFailure);
  EXPECT_EQ(run_command({"dxl", "", throws_an_int}, 1, argv), kExitFailure);
  EXPECT_EQ(run_command({"vbus", "", returns_bad_input}, 1, argv), kExitBadInput);
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "stride report: internal error: json.exception.type_error.302: type must be number\n"
            "stride sim: internal error: std::bad_alloc\n"
            "stride dxl: internal error: an unknown exception\n");
}

}  // namespace
}  // namespace stride::tools
