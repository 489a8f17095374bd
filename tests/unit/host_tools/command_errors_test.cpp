// CommandErrors (command_errors.hpp): one line "stride COMMAND: message" on stderr, exit 2 for bad
// input and 1 for a failure; a warning says so and returns nothing.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace stride::tools
