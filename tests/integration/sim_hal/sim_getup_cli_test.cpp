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

// The authored get-up scripts the getup run started from (optimiser/configs/getup-start/), as a
// parameter file of getup.json's start genome: the firmware's default get-up before it carried
// the run's pick.
std::string authored_scripts_file() {
  nlohmann::json config;
  std::ifstream(std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/getup.json") >> config;
  nlohmann::json params = nlohmann::json::object();
  for (const nlohmann::json& gene : config.at("genes")) {
    params[gene.at("parameter").get<std::string>()] = gene.at("start");
  }
  const std::string file = ::testing::TempDir() + "/getup-authored.json";
  std::ofstream(file) << params.dump();
  return file;
}

// Measured on this branch (default world: Simbody, identified servo, CM730 IMU, turf, seed 1,
// noise on): the default firmware's get-up scripts carry the get-up run's knee
// (get-up-turf.json, kept as the record of the pick) and stand up from both sides, the same
// episodes as with --params get-up-turf.json; their mean, (7.20 + 12.35) / 2 = 9.78 s, is the
// figure of optimiser/RESULTS.md ("Get-up run"). The authored scripts stayed down from the back
// on Simbody's turf (three attempts in 20 s), as issue 43 said.
TEST(StrideSimGetUp, TheDefaultFirmwareStandsUpOnSimbodysTurfFromTheBack) {
  const nlohmann::json back = sim_json("getup --lying back");
  EXPECT_NEAR(stood_up_s(back), 7.20, 1e-9) << back.dump();
  EXPECT_EQ(back.at("lying"), "back");
  EXPECT_EQ(back.at("get_up_script"), "get_up_back");
  EXPECT_EQ(back.at("get_up_attempts"), 1);
  EXPECT_DOUBLE_EQ(back.at("sim_time_s").get<double>(), 20.0);  // the default duration
  EXPECT_EQ(back.at("status"), "running");
  // Deterministic: the same episode again.
  EXPECT_EQ(sim_json("getup --lying back").at("state_hash"), back.at("state_hash"));
  // The authored scripts stay down there.
  const nlohmann::json authored =
      sim_json("getup --lying back --params " + authored_scripts_file());
  EXPECT_TRUE(authored.at("stood_up_s").is_null()) << authored.dump();
  EXPECT_EQ(authored.at("get_up_attempts"), 3);
}

TEST(StrideSimGetUp, OnMujocoTheDefaultFirmwareStandsUpFromTheBack) {
  const nlohmann::json back = sim_json("getup --lying back --engine mujoco");
  EXPECT_NEAR(stood_up_s(back), 7.20, 1e-9) << back.dump();
  EXPECT_EQ(back.at("get_up_attempts"), 1);
}

TEST(StrideSimGetUp, TheDefaultFirmwareIsTheGetUpRunsKneeAndStandsUpFromBothSides) {
  const nlohmann::json back = sim_json("getup --lying back");
  EXPECT_NEAR(stood_up_s(back), 7.20, 1e-9) << back.dump();
  EXPECT_EQ(back.at("get_up_attempts"), 1);
  const nlohmann::json front = sim_json("getup --lying front");
  EXPECT_NEAR(stood_up_s(front), 12.35, 1e-9) << front.dump();
  EXPECT_EQ(front.at("get_up_script"), "get_up_front");  // rolls onto its back, then get_up_back
  EXPECT_EQ(front.at("get_up_attempts"), 2);
  // get-up-turf.json changes nothing: bit for bit the same episodes.
  EXPECT_EQ(sim_json("getup --lying back --params " + kGetUpTurf).at("state_hash"),
            back.at("state_hash"));
  EXPECT_EQ(sim_json("getup --lying front --params " + kGetUpTurf).at("state_hash"),
            front.at("state_hash"));
  // A duration that ends before the robot has stood for the held second: null.
  const nlohmann::json short_one = sim_json("getup --lying back --duration 8");
  EXPECT_TRUE(short_one.at("stood_up_s").is_null()) << short_one.dump();
}

// Where the authored scripts stood up, the default firmware does too, no slower than 0.1 s:
// on the seed's 2 cm grass from the back on Simbody 7.20 s (authored 7.10 s), from the front on
// MuJoCo 12.07 s (authored 16.87 s, three attempts).
TEST(StrideSimGetUp, OnTheSeedsGrassTheDefaultFirmwareStandsUpToo) {
  const nlohmann::json back = sim_json("getup --lying back --contact seed");
  EXPECT_NEAR(stood_up_s(back), 7.20, 1e-9) << back.dump();
  EXPECT_NEAR(
      stood_up_s(sim_json("getup --lying back --contact seed --params " + authored_scripts_file())),
      7.10, 1e-9);
  const nlohmann::json front = sim_json("getup --lying front --contact seed --engine mujoco");
  EXPECT_NEAR(stood_up_s(front), 12.07, 1e-9) << front.dump();
  EXPECT_EQ(front.at("get_up_attempts"), 2);
  const nlohmann::json authored = sim_json(
      "getup --lying front --contact seed --engine mujoco "
      "--params " +
      authored_scripts_file());
  EXPECT_NEAR(stood_up_s(authored), 16.87, 1e-9) << authored.dump();
  EXPECT_EQ(authored.at("get_up_attempts"), 3);
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
  EXPECT_NE(page.str().find("stood up after 7.20 s"), std::string::npos);
  EXPECT_NE(page.str().find("lying on the back"), std::string::npos);
}

TEST(StrideSimGetUp, APushedRobotGoesOnThroughItsGetUpWithAfterFall) {
  // Pushed backward at 1 s (4 N s) it falls on its back at 1.85 s. Without --after-fall the
  // episode ends there; with it the episode runs its 30 s and the robot stands up 7.17 s after
  // the fall (the default get-up, the get-up run's knee). (Before the fall protection,
  // firmware/src/FALLING.md: 1.83 s and 7.21 s; the firmware now predicts the fall at 1.60 s and
  // lands crouched.)
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
  EXPECT_NEAR(stood_up_s(went_on), 7.17, 1e-9) << went_on.dump();
  EXPECT_EQ(went_on.at("get_up_script"), "get_up_back");
  EXPECT_FALSE(went_on.contains("lying"));
  // Walking, pushed forward (8 N s at 3 s), the default firmware stands up 12.53 s after the
  // fall (fall at 3.30 s; before the fall protection 3.41 s and 11.87 s), in two attempts; the
  // authored scripts tried four times and stayed down on Simbody's turf.
  const std::string walk = "walk --vx 1 --push 3,forward,8 --after-fall getup";
  const nlohmann::json walked = sim_json(walk);
  EXPECT_NEAR(walked.at("fall_time_s").get<double>(), 3.30, 1e-9);
  EXPECT_DOUBLE_EQ(walked.at("sim_time_s").get<double>(), 30.0);
  EXPECT_NEAR(stood_up_s(walked), 12.53, 1e-9) << walked.dump();
  EXPECT_EQ(walked.at("get_up_attempts"), 2);
  const nlohmann::json authored = sim_json(walk + " --params " + authored_scripts_file());
  EXPECT_TRUE(authored.at("stood_up_s").is_null()) << authored.dump();
  EXPECT_EQ(authored.at("get_up_attempts"), 4);
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
