// Integration tests (release build) of `stride sim getup --lying front|back` and
// `stride sim stand|walk --after-fall getup` (issue 43 point 1): the time from lying still to
// standing (stood_up_s) as measured in the default world, deterministic and asserted; a pushed
// robot's episode goes on past its fall through the get-up; the replay options record the same
// episode; bad input is one line naming the option, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "run_command.hpp"

namespace {

const std::string kGetUpTurf = std::string(STRIDE_SOURCE_DIR) + "/firmware/config/get-up-turf.json";

nlohmann::json sim_json(const std::string& args) {
  int code = -1;
  const std::string out = stride::test::run_command(
      std::string(STRIDE_BIN_DIR) + "/stride sim " + args + " --json", code);
  EXPECT_EQ(code, 0) << args << ": " << out;
  return out.empty() ? nlohmann::json::object() : nlohmann::json::parse(out);
}

// Seconds from lying still to standing, or -1 for null (stayed down).
double stood_up_s(const nlohmann::json& result) {
  const nlohmann::json& value = result.at("stood_up_s");
  return value.is_null() ? -1.0 : value.get<double>();
}

// Measured on this branch (default world: Simbody, identified servo, CM730 IMU, turf, seed 1,
// noise on): the stock scripts stay down from the back on Simbody's turf (three attempts in
// 20 s), as issue 43 says; on MuJoCo they stand up. get-up-turf.json (the get-up run's knee)
// stands up from both sides; its mean, (7.20 + 12.35) / 2 = 9.78 s, is the figure of
// optimiser/RESULTS.md ("Get-up run").
TEST(StrideSimGetUp, TheDefaultFirmwareStaysDownOnSimbodysTurfFromTheBack) {
  const nlohmann::json back = sim_json("getup --lying back");
  EXPECT_TRUE(back.at("stood_up_s").is_null()) << back.dump();
  EXPECT_EQ(back.at("lying"), "back");
  EXPECT_EQ(back.at("get_up_script"), "get_up_back");
  EXPECT_EQ(back.at("get_up_attempts"), 3);
  EXPECT_DOUBLE_EQ(back.at("sim_time_s").get<double>(), 20.0);  // the default duration
  EXPECT_EQ(back.at("status"), "running");
  // Deterministic: the same episode again.
  EXPECT_EQ(sim_json("getup --lying back").at("state_hash"), back.at("state_hash"));
}

TEST(StrideSimGetUp, OnMujocoTheStockScriptsStandUpFromTheBack) {
  const nlohmann::json back = sim_json("getup --lying back --engine mujoco");
  EXPECT_NEAR(stood_up_s(back), 7.10, 1e-9) << back.dump();
  EXPECT_EQ(back.at("get_up_attempts"), 1);
}

TEST(StrideSimGetUp, TheGetUpRunsKneeStandsUpFromBothSides) {
  const nlohmann::json back = sim_json("getup --lying back --params " + kGetUpTurf);
  EXPECT_NEAR(stood_up_s(back), 7.20, 1e-9) << back.dump();
  EXPECT_EQ(back.at("get_up_attempts"), 1);
  const nlohmann::json front = sim_json("getup --lying front --params " + kGetUpTurf);
  EXPECT_NEAR(stood_up_s(front), 12.35, 1e-9) << front.dump();
  EXPECT_EQ(front.at("get_up_script"), "get_up_front");  // rolls onto its back, then get_up_back
  EXPECT_EQ(front.at("get_up_attempts"), 2);
  // A duration that ends before the robot has stood for the held second: null.
  const nlohmann::json short_one =
      sim_json("getup --lying back --duration 8 --params " + kGetUpTurf);
  EXPECT_TRUE(short_one.at("stood_up_s").is_null()) << short_one.dump();
}

TEST(StrideSimGetUp, RecordAndHtmlReplayTheSameEpisode) {
  const std::string dir = ::testing::TempDir();
  const std::string record = dir + "/getup.jsonl", html = dir + "/getup.html";
  const nlohmann::json plain = sim_json("getup --lying back --params " + kGetUpTurf);
  const nlohmann::json replayed = sim_json("getup --lying back --params " + kGetUpTurf +
                                           " --record " + record + " --html " + html);
  EXPECT_EQ(replayed.at("state_hash"), plain.at("state_hash"));
  std::ifstream record_file(record);
  std::string line;
  int lines = 0;
  while (std::getline(record_file, line)) ++lines;
  EXPECT_GE(lines, 2001);  // every tick of the 20 s
  std::stringstream page;
  page << std::ifstream(html).rdbuf();
  EXPECT_NE(page.str().find("stood up after 7.20 s"), std::string::npos);
  EXPECT_NE(page.str().find("lying on the back"), std::string::npos);
}

TEST(StrideSimGetUp, APushedRobotGoesOnThroughItsGetUpWithAfterFall) {
  // Pushed backward at 1 s (4 N s) it falls on its back at 1.83 s. Without --after-fall the
  // episode ends there; with it the episode runs its 30 s and the robot stands up 7.21 s after
  // the fall (get-up-turf.json).
  const std::string push = "stand --push 1,backward,4 --params " + kGetUpTurf;
  const nlohmann::json ended = sim_json(push);
  EXPECT_TRUE(ended.at("fell").get<bool>());
  EXPECT_NEAR(ended.at("fall_time_s").get<double>(), 1.83, 1e-9);
  EXPECT_NEAR(ended.at("sim_time_s").get<double>(), 1.83, 1e-9);
  EXPECT_FALSE(ended.contains("stood_up_s"));
  const nlohmann::json went_on = sim_json(push + " --after-fall getup");
  EXPECT_TRUE(went_on.at("fell").get<bool>());
  EXPECT_NEAR(went_on.at("fall_time_s").get<double>(), 1.83, 1e-9);
  EXPECT_DOUBLE_EQ(went_on.at("sim_time_s").get<double>(), 30.0);
  EXPECT_NEAR(stood_up_s(went_on), 7.21, 1e-9) << went_on.dump();
  EXPECT_EQ(went_on.at("get_up_script"), "get_up_back");
  EXPECT_FALSE(went_on.contains("lying"));
  // Walking, pushed forward (8 N s at 3 s), the default firmware tries four times and stays
  // down on Simbody's turf; get-up-turf.json stands up 11.87 s after the fall.
  const std::string walk = "walk --vx 1 --push 3,forward,8 --after-fall getup";
  const nlohmann::json stock = sim_json(walk);
  EXPECT_NEAR(stock.at("fall_time_s").get<double>(), 3.41, 1e-9);
  EXPECT_DOUBLE_EQ(stock.at("sim_time_s").get<double>(), 30.0);
  EXPECT_TRUE(stock.at("stood_up_s").is_null()) << stock.dump();
  EXPECT_EQ(stock.at("get_up_attempts"), 4);
  EXPECT_NEAR(stood_up_s(sim_json(walk + " --params " + kGetUpTurf)), 11.87, 1e-9);
}

TEST(StrideSimGetUp, BadInputIsOneLineNamingTheOptionAndExitTwo) {
  const std::pair<const char*, const char*> cases[] = {
      {"getup --lying sideways", "--lying"},
      {"getup", "--lying"},
      {"walk --lying back", "--lying"},
      {"stand --lying front", "--lying"},
      {"kick --lying back", "--lying"},
      {"stand --after-fall kick", "--after-fall"},
      {"walk --after-fall ''", "--after-fall"},
      {"getup --lying back --after-fall getup", "--after-fall"},
      {"kick --after-fall getup", "--after-fall"},
  };
  for (const auto& [args, option] : cases) {
    int code = -1;
    const std::string err = stride::test::run_command(
        std::string(STRIDE_BIN_DIR) + "/stride sim " + args + " --json 2>&1 >/dev/null", code);
    EXPECT_EQ(code, 2) << args << ": " << err;
    EXPECT_NE(err.find(option), std::string::npos) << args << ": " << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << args << ": " << err;
  }
}

}  // namespace
