// `stride-fw --hal sim --world seed` is the thesis's world and its walk, as `stride sim --world
// seed` is (issue 55 point 3): without --params the firmware loads the seed world's walk
// defaults (config/seed-walk.json); --params still chooses another file, and the default
// (faithful) world loads none. Read back from the flight log's header, which names the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "run_command.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "temp_dir.hpp"

namespace stride::sim {
namespace {

const std::string kStrideFw = std::string(STRIDE_BIN_DIR) + "/stride-fw --hal sim --no-rt ";

std::string params_file_of(const std::string& options) {
  test::TempDir dir;
  const std::string log_path = (dir.path() / "run.flog").string();
  int code = -1;
  const std::string out = test::run_command(
      kStrideFw + "--ticks 2 --record " + log_path + " " + options + " 2>&1", code);
  EXPECT_EQ(code, 0) << options << ": " << out;
  fw::FlightLog log;
  const Status s = fw::read_flight_log(log_path, log);
  EXPECT_TRUE(s) << s.message();
  return s ? log.header["params_file"].get<std::string>() : "?";
}

TEST(StrideFwSimWorld, TheSeedWorldLoadsTheSeedsWalkUnlessParamsSaysOtherwise) {
  const std::string seed_walk = params_file_of("--world seed");
  EXPECT_EQ(std::filesystem::path(seed_walk).filename(), "seed-walk.json") << seed_walk;
  EXPECT_TRUE(std::filesystem::exists(seed_walk)) << seed_walk;
  test::TempDir dir;
  const auto mine = dir.path() / "mine.json";
  std::ofstream(mine) << "{}\n";
  EXPECT_EQ(params_file_of("--world seed --params " + mine.string()), mine.string());
  EXPECT_EQ(params_file_of(""), "");  // the faithful world: the firmware's defaults
}

}  // namespace
}  // namespace stride::sim
