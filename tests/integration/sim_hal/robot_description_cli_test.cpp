// The firmware's robot description: `stride describe` writes the shipped
// firmware/config/robot_description.json from the shipped URDF (so the file matches the model the
// simulator runs); stride-fw refuses to start on a description that does not match its servo
// table, with one line naming the field, exit 2; bad input to `stride describe` is one line.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "read_file.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"

namespace stride::sim {
namespace {

namespace fs = std::filesystem;
const std::string kBin = std::string(STRIDE_BIN_DIR);
const fs::path kShipped = fs::path(STRIDE_SOURCE_DIR) / "firmware/config/robot_description.json";

TEST(RobotDescriptionCli, TheShippedDescriptionIsWhatDescribeWritesFromTheShippedUrdf) {
  test::TempDir dir;
  int code = -1;
  test::run_command(kBin + "/stride describe --out " + (dir.path() / "d.json").string() +
                        " 2>/dev/null",
                    code);
  ASSERT_EQ(code, 0);
  EXPECT_EQ(test::read_file(dir.path() / "d.json"), test::read_file(kShipped));
}

TEST(RobotDescriptionCli, StrideFwWillNotStartOnADescriptionThatDoesNotMatchItsServoTable) {
  test::TempDir dir;
  nlohmann::json doc = nlohmann::json::parse(test::read_file(kShipped));
  doc["joints"][2]["servo"] = "l_wing";
  const fs::path bad = dir.write("robot.json", doc.dump());
  int code = -1;
  const std::string err = (dir.path() / "err.txt").string();
  test::run_command(kBin + "/stride-fw --hal test --ticks 5 --no-rt --robot-description " +
                        bad.string() + " 2>" + err,
                    code);
  EXPECT_EQ(code, 2);
  const std::string message = test::read_file(err);
  EXPECT_NE(message.find("robot.json.joints[2].servo: 'l_wing' is not in the servo table"),
            std::string::npos)
      << message;
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
  // The shipped description starts.
  test::run_command(kBin + "/stride-fw --hal test --ticks 5 --no-rt 2>/dev/null", code);
  EXPECT_EQ(code, 0);
}

TEST(RobotDescriptionCli, BadInputToDescribeIsOneLineAndExitTwo) {
  test::TempDir dir;
  int code = -1;
  const std::string err = (dir.path() / "err.txt").string();
  test::run_command(kBin + "/stride describe --urdf /nonexistent.urdf 2>" + err, code);
  EXPECT_EQ(code, 2);
  EXPECT_EQ(test::read_file(err).rfind("stride describe: --urdf: ", 0), 0U) << test::read_file(err);
  const fs::path out = dir.path() / "missing-dir" / "d.json";
  test::run_command(kBin + "/stride describe --out " + out.string() + " 2>" + err, code);
  EXPECT_EQ(code, 2);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace stride::sim
