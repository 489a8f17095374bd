// The project's contract for bad input on the command line, as a test assertion: exit 2, exactly
// one line on stderr naming what was wrong, nothing on stdout.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "child_process.hpp"

namespace stride::test {

inline void expect_bad_input(const ChildRun& run, const std::string& what) {
  EXPECT_EQ(run.code, 2) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_NE(run.err.find(what), std::string::npos) << run.err;
  EXPECT_EQ(run.out, "");
}

}  // namespace stride::test
