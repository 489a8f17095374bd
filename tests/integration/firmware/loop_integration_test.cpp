// The fixed-rate loop end to end: 1,000 ticks of the firmware on the scripted test HAL, a
// parameter batch landing at a tick boundary, and the stride-fw binary's command line.
#include <cstdio>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "stride/firmware/control_loop.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/firmware/stand_pose.hpp"
#include "stride/hal/scripted_robot.hpp"
#include "temp_dir.hpp"

namespace stride::fw {
namespace {

TEST(ControlLoop, ThousandTicksOnTheScriptedHal) {
  std::unique_ptr<Firmware> firmware;
  ASSERT_TRUE(Firmware::create({}, firmware));
  hal::ScriptedRobot::Options options;
  options.echo_commands = true;
  options.record_capacity = 1000;
  hal::ScriptedRobot robot(options, {hal::ScriptedRobot::standing_frame()});
  robot.inject_late_wakeup(600, 603);  // one overrun: 3 ticks lost
  ControlLoop loop(robot, firmware->controller(), firmware->params());

  loop.run(500);
  ASSERT_TRUE(firmware->params().stage({{"stand.gain", 50}}));
  loop.run(500);

  EXPECT_EQ(loop.counters().cycles, 1000u);
  EXPECT_EQ(loop.counters().missed_ticks, 3u);
  EXPECT_EQ(loop.counters().last_tick, 1002);
  EXPECT_EQ(loop.counters().param_batches, 1u);
  ASSERT_EQ(robot.recorded().size(), 1000u);
  // The batch lands exactly at the first tick after staging, never earlier.
  EXPECT_DOUBLE_EQ(robot.recorded()[499].servos[0].p_gain, 76.0);
  EXPECT_DOUBLE_EQ(robot.recorded()[500].servos[0].p_gain, 127.0);
  // The ideal servos followed the stand ramp into the stand pose.
  const auto& last = loop.last_sensors();
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    EXPECT_NEAR(last.servos[i].position_rad, kStandPoseRad[i], 1e-9) << i;
  }
}

// Runs a shell command; returns stdout (and stderr unless `stdout_only`).
std::string run(const std::string& command, int& exit_code, bool stdout_only = false) {
  std::string output;
  FILE* pipe = popen((command + (stdout_only ? " 2>/dev/null" : " 2>&1")).c_str(), "r");
  if (pipe == nullptr) return output;
  char buffer[512];
  while (fgets(buffer, sizeof buffer, pipe) != nullptr) output += buffer;
  const int status = pclose(pipe);
  exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return output;
}

TEST(StrideFw, RunsTheTestHalAndReportsJson) {
  int code = -1;
  const std::string out = run(
      std::string(STRIDE_BIN_DIR) + "/stride-fw --hal test --ticks 50 --no-rt --json", code, true);
  ASSERT_EQ(code, 0) << out;
  const auto report = nlohmann::json::parse(out);
  EXPECT_EQ(report["cycles"], 50);
  EXPECT_EQ(report["hal"], "test");
  EXPECT_TRUE(report.contains("jitter_us"));
  EXPECT_GT(report["jitter_us"]["max"].get<double>(), 0.0);
}

TEST(StrideFw, BrokenParameterFileIsRefusedWithTheFieldNamed) {
  test::TempDir dir;
  const auto params = dir.write("p.json", R"({"stand": {"gain": 500}})");
  int code = -1;
  const std::string out = run(std::string(STRIDE_BIN_DIR) +
                                  "/stride-fw --hal test --ticks 5 "
                                  "--params " +
                                  params.string(),
                              code);
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("stand.gain"), std::string::npos) << out;
  EXPECT_NE(out.find("[5, 100]"), std::string::npos) << out;
}

TEST(StrideFw, UnknownOptionsAndBackendsAreOneLineErrors) {
  int code = -1;
  std::string out = run(std::string(STRIDE_BIN_DIR) + "/stride-fw --hal warp", code);
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("unknown --hal 'warp'"), std::string::npos) << out;
  out = run(std::string(STRIDE_BIN_DIR) + "/stride-fw --tick 5", code);
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("--tick"), std::string::npos) << out;
}

}  // namespace
}  // namespace stride::fw
