// `stride sim servo` (issue 20 point 2): the bench experiments through the command line, and
// its bad-input contract (one line naming the option and what is allowed, exit 2); the world
// options `--urdf`, `--servo-law` and `--imu` of `stride sim`.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "run_command.hpp"
#include "temp_dir.hpp"

namespace {

std::string run_stride(const std::string& args, int& code) {
  return stride::test::run_command(std::string(STRIDE_BIN_DIR) + "/stride " + args, code);
}

TEST(StrideSimServo, NoLoadBlockedAndPendulumAsJson) {
  int code = -1;
  auto j = nlohmann::json::parse(
      run_stride("sim servo --model mx106 --experiment no-load --voltage 12 --json", code));
  EXPECT_EQ(code, 0);
  EXPECT_NEAR(j.at("speed_rad_s").get<double>(), 4.983, 0.05 * 4.983);  // servos.md, 12 V
  j = nlohmann::json::parse(run_stride(
      "sim servo --model mx106 --experiment blocked --voltage 15 --p-gain 10 --error-deg 12.57 "
      "--json",
      code));
  EXPECT_EQ(code, 0);
  EXPECT_NEAR(j.at("duty").get<double>(), 14.8 / 42.7, 0.05 * 14.8 / 42.7);  // servos.md row
  EXPECT_GT(j.at("torque_nm").get<double>(), 0.0);
  j = nlohmann::json::parse(run_stride(
      "sim servo --model mx64 --experiment pendulum --trajectory sin-sin --arm-length 0.1 "
      "--arm-mass 0.3 --duration 2 --json",
      code));
  EXPECT_EQ(code, 0);
  const auto& trace = j.at("trace");
  ASSERT_EQ(trace.size(), 201u);
  for (const char* field : {"t", "goal", "position", "speed", "torque"})
    EXPECT_TRUE(trace.back().contains(field)) << field;
  // It follows the trajectory within a tenth of a radian once moving.
  EXPECT_NEAR(trace[150].at("position").get<double>(), trace[150].at("goal").get<double>(), 0.1);
}

TEST(StrideSimServo, BadInputNamesTheOptionAndExitsTwo) {
  int code = -1;
  std::string err = run_stride("sim servo --model mx28 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 2);
  EXPECT_EQ(err, "stride sim servo: --model: unknown 'mx28' (allowed: mx64, mx106)\n");
  err = run_stride("sim servo --voltage 99 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 2);
  EXPECT_EQ(err.rfind("stride sim servo: --voltage: ", 0), 0u) << err;
  err = run_stride("sim servo --experiment pendulum --trajectory circle 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 2);
  EXPECT_NE(err.find("--trajectory: unknown 'circle'"), std::string::npos) << err;
  err = run_stride("sim servo --p-gain 300 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 2);
  EXPECT_NE(err.find("--p-gain"), std::string::npos) << err;
  err = run_stride("sim stand --servo-law gazebo 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 2);
  EXPECT_NE(err.find("--servo-law: expected seed or identified"), std::string::npos) << err;
  err = run_stride("sim stand --imu perfect 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 2);
  EXPECT_NE(err.find("--imu: expected ideal, cm730 or cm730-nimbro"), std::string::npos) << err;
}

// Another robot description: the igus model with a trunk 10 % heavier is what gets simulated.
TEST(StrideSimWorldOptions, UrdfSelectsTheRobotDescription) {
  stride::test::TempDir dir;
  std::ifstream in(std::string(STRIDE_SIM_MODEL_DIR) + "/igus_op.urdf");
  std::stringstream text;
  text << in.rdbuf();
  std::string urdf = text.str();
  const std::string trunk_mass = "<mass value=\"1.8051\"/>";
  const std::size_t at = urdf.find(trunk_mass);
  ASSERT_NE(at, std::string::npos);
  urdf.replace(at, trunk_mass.size(), "<mass value=\"1.98561\"/>");
  const std::string heavy = (dir.path() / "heavy_trunk.urdf").string();
  std::ofstream(heavy) << urdf;
  const std::string broken = (dir.path() / "broken.urdf").string();
  std::ofstream(broken) << "<robot name=\"x\"><link name=";

  int code = -1;
  auto stand = [&](const std::string& extra) {
    const auto j = nlohmann::json::parse(
        run_stride("sim stand --duration 1 --seed 2 --json " + extra + " 2>/dev/null", code));
    EXPECT_EQ(code, 0) << extra;
    return j.at("state_hash").get<std::string>();
  };
  const std::string stock = stand("");
  EXPECT_EQ(stand("--urdf " + std::string(STRIDE_SIM_MODEL_DIR) + "/igus_op.urdf"), stock);
  EXPECT_NE(stand("--urdf " + heavy), stock);
  std::string err = run_stride("sim stand --urdf " + broken + " 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 2);
  EXPECT_EQ(err.rfind("stride sim: --urdf: ", 0), 0u) << err;
  err = run_stride("sim stand --urdf /nonexistent.urdf 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 2);
  EXPECT_EQ(err, "stride sim: --urdf: no such file '/nonexistent.urdf'\n");
}

}  // namespace

// The physics engine: the same stand on MuJoCo is another simulation, repeatable; a name that
// is not an engine is one line and exit 2.
TEST(StrideSimWorldOptions, EngineSelectsThePhysics) {
  int code = -1;
  auto stand = [&](const std::string& extra) {
    const auto j = nlohmann::json::parse(
        run_stride("sim stand --duration 1 --seed 2 --json " + extra + " 2>/dev/null", code));
    EXPECT_EQ(code, 0) << extra;
    EXPECT_FALSE(j.at("fell").get<bool>()) << extra;
    return j.at("state_hash").get<std::string>();
  };
  const std::string simbody = stand("");
  EXPECT_EQ(stand("--engine simbody"), simbody);
  const std::string mujoco = stand("--engine mujoco");
  EXPECT_NE(mujoco, simbody);
  EXPECT_EQ(stand("--engine mujoco"), mujoco);
  const std::string err = run_stride("sim stand --engine bullet 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 2);
  EXPECT_EQ(err, "stride sim: --engine: expected simbody or mujoco, got 'bullet'\n");
}
