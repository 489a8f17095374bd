// stride console client helpers: final-line detection and flash --verify's value comparison.
#include "stride/host_tools/console_client.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace stride::tools {
namespace {

TEST(ConsoleClient, FinalLines) {
  EXPECT_TRUE(is_final_line("ok"));
  EXPECT_TRUE(is_final_line("ok stand.gain = 30"));
  EXPECT_TRUE(is_final_line("err usage get NAME"));
  EXPECT_FALSE(is_final_line("okay"));
  EXPECT_FALSE(is_final_line("error"));
  EXPECT_FALSE(is_final_line("stand.gain = 30  real [5, 100]"));
  EXPECT_FALSE(is_final_line(""));
}

TEST(ConsoleClient, VerifyComparesValues) {
  EXPECT_TRUE(value_matches(nlohmann::json(0.85), "0.85"));
  EXPECT_TRUE(value_matches(nlohmann::json(12), "12"));
  EXPECT_TRUE(value_matches(nlohmann::json(1e-5), "1e-05"));
  EXPECT_TRUE(value_matches(nlohmann::json(true), "true"));
  EXPECT_TRUE(value_matches(nlohmann::json(false), "false"));
  EXPECT_FALSE(value_matches(nlohmann::json(0.85), "0.86"));
  EXPECT_FALSE(value_matches(nlohmann::json(0.85), "0.85 s"));
  EXPECT_FALSE(value_matches(nlohmann::json(0.85), ""));
  EXPECT_FALSE(value_matches(nlohmann::json(true), "1"));
  EXPECT_FALSE(value_matches(nlohmann::json(1), "true"));
  EXPECT_FALSE(value_matches(nlohmann::json("fast"), "fast"));
}

}  // namespace
}  // namespace stride::tools
