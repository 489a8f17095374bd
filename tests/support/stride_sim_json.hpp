// `stride sim ... --json` from the integration tests: the result object of one episode, and its
// stood_up_s with a robot that stayed down as 1e9 s (slower than any that stood).
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "run_command.hpp"

namespace stride::test {

/// Runs `stride sim ARGS --json`; a failing exit is a test failure naming the arguments.
inline nlohmann::json sim_json(const std::string& args) {
  int code = -1;
  const std::string out =
      run_command(std::string(STRIDE_BIN_DIR) + "/stride sim " + args + " --json", code);
  EXPECT_EQ(code, 0) << args << ": " << out;
  return out.empty() ? nlohmann::json::object() : nlohmann::json::parse(out);
}

/// Seconds to standing, or 1e9 for null (stayed down).
inline double stood_up_s(const nlohmann::json& result) {
  const nlohmann::json& value = result.at("stood_up_s");
  return value.is_null() ? 1e9 : value.get<double>();
}

}  // namespace stride::test
