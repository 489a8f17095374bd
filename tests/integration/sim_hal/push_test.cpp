// Integration tests (release build): a push on the trunk (TorsoPush, `stride sim walk --push
// T,DIR,IMPULSE`, issue 29 point 4) gives the body the momentum of its impulse on both engines,
// changes the outcome deterministically, and a malformed or out-of-range push is one line naming
// the option and exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "run_command.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_cli.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace stride::sim {
namespace {

/// Mass of the robot model (no randomisation in these worlds) [kg].
double robot_mass(const SimWorld& world) {
  double mass = 0.0;
  for (const LinkSpec& link : world.model().links()) mass += link.mass;
  return mass;
}

/// Centre of mass of the robot after `world`'s next control period.
Eigen::Vector3d com_after_next_period(SimWorld& world) {
  world.advance_period();
  return world.ground_truth().center_of_mass;
}

// The robot standing with its servos holding the Stand pose, pushed at 1 s with 1 N s to its
// left: over the 10 ms of the push its centre of mass gains about 1 N s / 6.46 kg = 0.155 m/s
// to the left (the feet's friction takes a little), and nothing forward.
TEST(SimPush, ThePushGivesTheBodyTheMomentumOfItsImpulseOnBothEngines) {
  for (EngineKind engine : {EngineKind::kSimbody, EngineKind::kMujoco}) {
    WorldOptions options;
    options.engine = engine;
    options.pushes.push_back({1.0, M_PI / 2, 1.0});
    std::unique_ptr<SimWorld> world;
    ASSERT_TRUE(SimWorld::create(options, world));
    const StepFunction hold = hold_pose_controller(igus_stand_pose());
    SimRobot robot(std::move(world));
    hal::SensorFrame sensors;
    for (hal::Tick tick = 0; tick < 99; ++tick) {  // to t = 0.99 s
      robot.read(sensors);
      robot.write(hold(sensors, tick));
      robot.sleep_until(tick + 1);
    }
    SimWorld& w = robot.world();
    const Eigen::Vector3d c099 = w.ground_truth().center_of_mass;
    const Eigen::Vector3d c100 = com_after_next_period(w);  // the push acts from 1.00 s
    const Eigen::Vector3d c101 = com_after_next_period(w);  // to 1.01 s
    const Eigen::Vector3d c102 = com_after_next_period(w);
    const Eigen::Vector3d change = (c102 - c101) / 0.01 - (c100 - c099) / 0.01;
    const double expected = 1.0 / robot_mass(w);
    std::printf("%s: centre-of-mass velocity change %.4f %.4f m/s (impulse / mass %.4f)\n",
                to_string(engine), change.x(), change.y(), expected);
    EXPECT_NEAR(change.y(), expected, 0.25 * expected) << to_string(engine);
    EXPECT_LT(std::abs(change.x()), 0.2 * expected) << to_string(engine);
  }
}

std::string run(const std::string& args, int& code) {
  return stride::test::run_command(std::string(STRIDE_BIN_DIR) + "/stride " + args, code);
}

std::string hash_of(const std::string& args) {
  int code = -1;
  const std::string out = run("sim walk --vx 1 --duration 4 --seed 2 --json " + args, code);
  EXPECT_TRUE(code == 0 || code == 1) << out;
  return nlohmann::json::parse(out)["state_hash"].get<std::string>();
}

TEST(StrideSimPush, APushChangesTheOutcomeDeterministicallyOnBothEngines) {
  for (const std::string engine : {"simbody", "mujoco"}) {
    const std::string pushed = hash_of("--engine " + engine + " --push 2.5,left,1");
    EXPECT_EQ(pushed, hash_of("--engine " + engine + " --push 2.5,left,1")) << engine;
    EXPECT_NE(pushed, hash_of("--engine " + engine)) << engine;
    EXPECT_NE(pushed, hash_of("--engine " + engine + " --push 2.5,right,1")) << engine;
    // Repeatable: a second push changes it again; the same push as degrees is the same push.
    EXPECT_NE(pushed, hash_of("--engine " + engine + " --push 2.5,left,1 --push=3,0,0.5"));
    EXPECT_EQ(pushed, hash_of("--engine " + engine + " --push 2.5,90,1"));
  }
}

TEST(StrideFwSimPush, TheFirmwareOnTheSimHalTakesPushesToo) {
  // stride-fw --hal sim reads the same world options (sim_cli): the push lands in its report's
  // state hash, deterministically; a bad one is one line naming --push.
  auto fw_hash = [](const std::string& extra) {
    int code = -1;
    const std::string out = stride::test::run_command(
        std::string(STRIDE_BIN_DIR) + "/stride-fw --hal sim --ticks 400 --no-rt --json " + extra +
            " 2>/dev/null",
        code);
    EXPECT_EQ(code, 0) << extra;
    return nlohmann::json::parse(out)["sim"]["state_hash"].get<std::string>();
  };
  const std::string pushed = fw_hash("--push 2,forward,2");
  EXPECT_EQ(pushed, fw_hash("--push 2,forward,2"));
  EXPECT_NE(pushed, fw_hash(""));
  int code = -1;
  const std::string err = stride::test::run_command(
      std::string(STRIDE_BIN_DIR) + "/stride-fw --hal sim --ticks 10 --no-rt --push 1,up,1 2>&1",
      code);
  EXPECT_EQ(code, 2) << err;  // bad input (DESIGN.md "Command-line contract")
  EXPECT_NE(err.find("--push: direction must be"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

TEST(StrideSimPush, MalformedOrOutOfRangeIsOneLineNamingTheOptionAndExitTwo) {
  for (const char* push : {"1,forward", "1,forward,1,2", "x,forward,1", "1,up,1", "1,forward,0",
                           "1,forward,-1", "1,forward,21", "-1,forward,1", "10,forward,1",
                           "1,400,1", "1,forward,nan", "", "1,,1", "1,forward,1,"}) {
    int code = -1;
    const std::string err =
        run("sim walk --duration 10 --push '" + std::string(push) + "' 2>&1 >/dev/null", code);
    EXPECT_EQ(code, 2) << push;
    EXPECT_NE(err.find("--push"), std::string::npos) << push << ": " << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << push << ": " << err;
  }
  TorsoPush parsed;
  ASSERT_TRUE(parse_push("2.5,right,1.5", 10.0, parsed));
  EXPECT_DOUBLE_EQ(parsed.time_s, 2.5);
  EXPECT_DOUBLE_EQ(parsed.direction_rad, -M_PI / 2);
  EXPECT_DOUBLE_EQ(parsed.impulse_n_s, 1.5);
}

}  // namespace
}  // namespace stride::sim
