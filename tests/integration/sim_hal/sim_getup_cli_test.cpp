// Integration tests (release build) of `stride sim getup --lying front|back` and
// `stride sim stand|walk --after-fall getup` (issue 43 point 1): the time from lying still to
// standing (stood_up_s) as measured in the default world, deterministic and asserted; a pushed
// robot's episode goes on past its fall through the get-up; the replay options record the same
// episode; bad input is one line naming the option, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "run_command.hpp"

namespace {

// Measured on this branch, default world, seed 1: seconds to standing.
constexpr double kBackSimbodyS = 2.28, kFrontSimbodyS = 2.42;  // from lying still
constexpr double kBackMujocoS = 2.32, kFrontMujocoS = 2.46;
constexpr double kPushedBackS = 2.12;  // stand, pushed backward: from the fall
constexpr double kWalkPushedS = 5.06;  // walking, pushed forward: from the fall, two attempts

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

// Measured on this branch (default world: identified servo, CM730 IMU, turf, seed 1, noise on):
// the default firmware's direct get-ups (issue 43) stand up from both sides on both engines at
// the first try, in 2.2-2.5 s from lying still (0.2 s of it lying still before the script
// starts). Before issue 43 the same episodes took 7.20 s from the back and 12.35 s (Simbody) or
// 12.07 s (MuJoCo) from the front, which rolled onto its back and got up from there.
TEST(StrideSimGetUp, TheDefaultFirmwareStandsUpFromBothSidesOnBothEngines) {
  const struct {
    const char* args;
    double stood_up_s;
  } cases[] = {
      {"getup --lying back", kBackSimbodyS},
      {"getup --lying front", kFrontSimbodyS},
      {"getup --lying back --engine mujoco", kBackMujocoS},
      {"getup --lying front --engine mujoco", kFrontMujocoS},
  };
  for (const auto& c : cases) {
    const nlohmann::json r = sim_json(c.args);
    EXPECT_NEAR(stood_up_s(r), c.stood_up_s, 1e-9) << c.args << ": " << r.dump();
    EXPECT_LT(stood_up_s(r), 3.0) << c.args;  // issue 43's target
    EXPECT_EQ(r.at("get_up_attempts"), 1) << c.args;
    const bool back = std::string(c.args).find("back") != std::string::npos;
    EXPECT_EQ(r.at("lying"), back ? "back" : "front") << c.args;
    EXPECT_EQ(r.at("get_up_script"), back ? "get_up_back" : "get_up_front") << c.args;
    EXPECT_DOUBLE_EQ(r.at("sim_time_s").get<double>(), 20.0);  // the default duration
    EXPECT_EQ(r.at("status"), "running");
  }
  // Deterministic: the same episode again.
  EXPECT_EQ(sim_json("getup --lying back").at("state_hash"),
            sim_json("getup --lying back").at("state_hash"));
  // A duration that ends before the robot has stood for the held second: null.
  const nlohmann::json short_one = sim_json("getup --lying back --duration 3");
  EXPECT_TRUE(short_one.at("stood_up_s").is_null()) << short_one.dump();
}

// On the other grounds too, from both sides, under 3 s at the first try (Simbody and MuJoCo;
// before issue 43 the front stayed down on Simbody's soft ground and on MuJoCo's hard ground,
// and the back on MuJoCo's hard ground). One exception, measured: on MuJoCo's seed grass the back
// get-up falls back three times and stands at the fourth attempt, 8.94 s from lying still. The
// back script's mixed search stage traded it for the drawn worlds (optimiser/RESULTS.md, "Direct
// get-ups": with friction, masses and strength drawn it stands there in 18 of 20 seeds, the
// script before it in 12).
TEST(StrideSimGetUp, OnEveryGroundTheDefaultFirmwareStandsUpFromBothSides) {
  for (const char* engine : {"simbody", "mujoco"}) {
    for (const char* contact : {"seed", "soft", "hard"}) {
      for (const char* side : {"front", "back"}) {
        const bool exception = std::string(engine) == "mujoco" && std::string(contact) == "seed" &&
                               std::string(side) == "back";
        const std::string args = std::string("getup --lying ") + side + " --engine " + engine +
                                 " --contact " + contact +
                                 (exception ? " --duration 10" : " --duration 5");
        const nlohmann::json r = sim_json(args);
        if (exception) {
          EXPECT_NEAR(stood_up_s(r), 8.94, 1e-9) << args << ": " << r.dump();
          EXPECT_EQ(r.at("get_up_attempts"), 4) << args;
          continue;
        }
        EXPECT_GT(stood_up_s(r), 2.0) << args << ": " << r.dump();
        EXPECT_LT(stood_up_s(r), 3.0) << args << ": " << r.dump();
        EXPECT_EQ(r.at("get_up_attempts"), 1) << args;
      }
    }
  }
}

TEST(StrideSimGetUp, RecordAndHtmlReplayTheSameEpisode) {
  const std::string dir = ::testing::TempDir();
  const std::string record = dir + "/getup.jsonl", html = dir + "/getup.html";
  const nlohmann::json plain = sim_json("getup --lying back");
  const nlohmann::json replayed =
      sim_json("getup --lying back --record " + record + " --html " + html);
  EXPECT_EQ(replayed.at("state_hash"), plain.at("state_hash"));
  std::ifstream record_file(record);
  std::string line;
  int lines = 0;
  while (std::getline(record_file, line)) ++lines;
  EXPECT_GE(lines, 2001);  // every tick of the 20 s
  std::stringstream page;
  page << std::ifstream(html).rdbuf();
  char expected[64];
  std::snprintf(expected, sizeof expected, "stood up after %.2f s", kBackSimbodyS);
  EXPECT_NE(page.str().find(expected), std::string::npos) << expected;
  EXPECT_NE(page.str().find("lying on the back"), std::string::npos);
}

TEST(StrideSimGetUp, APushedRobotGoesOnThroughItsGetUpWithAfterFall) {
  // Pushed backward at 1 s (4 N s) it falls on its back at 1.85 s. Without --after-fall the
  // episode ends there; with it the episode runs its 30 s and the robot stands up
  // kPushedBackS after the fall with the direct get-up (7.17 s before issue 43).
  const std::string push = "stand --push 1,backward,4";
  const nlohmann::json ended = sim_json(push);
  EXPECT_TRUE(ended.at("fell").get<bool>());
  EXPECT_NEAR(ended.at("fall_time_s").get<double>(), 1.85, 1e-9);
  EXPECT_NEAR(ended.at("sim_time_s").get<double>(), 1.85, 1e-9);
  EXPECT_FALSE(ended.contains("stood_up_s"));
  const nlohmann::json went_on = sim_json(push + " --after-fall getup");
  EXPECT_TRUE(went_on.at("fell").get<bool>());
  EXPECT_NEAR(went_on.at("fall_time_s").get<double>(), 1.85, 1e-9);
  EXPECT_DOUBLE_EQ(went_on.at("sim_time_s").get<double>(), 30.0);
  EXPECT_NEAR(stood_up_s(went_on), kPushedBackS, 1e-9) << went_on.dump();
  EXPECT_EQ(went_on.at("get_up_script"), "get_up_back");
  EXPECT_FALSE(went_on.contains("lying"));
  // Walking, pushed forward (8 N s at 3 s), it falls at 3.30 s and stands up kWalkPushedS after
  // the fall (12.53 s before issue 43, the roll). The first front get-up fails here: the robot
  // lands in the crouch of the fall protection, not the lying pose the get-up was designed
  // from, and the second attempt stands.
  const std::string walk = "walk --vx 1 --push 3,forward,8 --after-fall getup";
  const nlohmann::json walked = sim_json(walk);
  EXPECT_NEAR(walked.at("fall_time_s").get<double>(), 3.30, 1e-9);
  EXPECT_DOUBLE_EQ(walked.at("sim_time_s").get<double>(), 30.0);
  EXPECT_NEAR(stood_up_s(walked), kWalkPushedS, 1e-9) << walked.dump();
  EXPECT_EQ(walked.at("get_up_script"), "get_up_front");
  EXPECT_EQ(walked.at("get_up_attempts"), 2);
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
