// One parameter chooses the walk engine (issue 53 point 1): a parameter file with walk.engine 1
// makes `stride sim` and `stride-fw` run the spline walk; without it (or with 0) they run the
// seed's walk exactly as before; a value that names no engine is refused naming the parameter.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "run_command.hpp"
#include "temp_dir.hpp"

namespace stride::sim {
namespace {

const std::string kBin = std::string(STRIDE_BIN_DIR);

std::string write(const test::TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = (dir.path() / name).string();
  std::ofstream(path) << text;
  return path;
}

std::string walk_hash(const std::string& extra) {
  int code = -1;
  const std::string out = test::run_command(
      kBin + "/stride sim walk --vx 1 --vy 0.3 --duration 4 --json " + extra, code);
  EXPECT_EQ(code, 0) << extra << ": " << out;
  return out.empty() ? "" : nlohmann::json::parse(out).at("state_hash").get<std::string>();
}

TEST(WalkEngineChoice, AParameterFileChoosesTheEngineForStrideSim) {
  test::TempDir dir;
  const std::string spline = write(dir, "spline.json", "{\"walk.engine\": 1}\n");
  const std::string seed = write(dir, "seed.json", "{\"walk\": {\"engine\": 0}}\n");
  const std::string none = walk_hash("");
  EXPECT_EQ(walk_hash("--params " + seed), none);  // the seed's walk is the default
  const std::string chosen = walk_hash("--params " + spline);
  EXPECT_NE(chosen, none);
  // The spline walk's own parameters take effect through the same file.
  const std::string slower =
      write(dir, "slower.json", "{\"walk.engine\": 1, \"walk.spline.frequency\": 1.2}\n");
  EXPECT_NE(walk_hash("--params " + slower), chosen);
}

TEST(WalkEngineChoice, AnEngineThatDoesNotExistIsRefusedNamingTheParameter) {
  test::TempDir dir;
  const std::string bad = write(dir, "bad.json", "{\"walk.engine\": 2}\n");
  int code = -1;
  const std::string out =
      test::run_command(kBin + "/stride sim walk --duration 1 --params " + bad + " 2>&1", code);
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("walk.engine"), std::string::npos) << out;
}

TEST(WalkEngineChoice, StrideFwTakesTheSameFile) {
  test::TempDir dir;
  const std::string spline = write(dir, "spline.json", "{\"walk.engine\": 1}\n");
  int code = -1;
  const std::string out = test::run_command(
      kBin + "/stride-fw --hal test --ticks 20 --no-rt --json --params " + spline, code);
  EXPECT_EQ(code, 0) << out;
  const std::string bad = write(dir, "bad.json", "{\"walk.spline.frequency\": 9}\n");
  const std::string refused = test::run_command(
      kBin + "/stride-fw --hal test --ticks 20 --no-rt --params " + bad + " 2>&1", code);
  EXPECT_EQ(code, 2) << refused;
  EXPECT_NE(refused.find("walk.spline.frequency"), std::string::npos) << refused;
}

}  // namespace
}  // namespace stride::sim
