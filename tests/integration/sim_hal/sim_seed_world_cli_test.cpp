// `stride sim --world seed` is the thesis's world and its walk (issue 44 point 2): without
// --params the controller loads the seed world's walk defaults (firmware/config/seed-walk.json),
// so the episode is exactly the one with that file given; --params still chooses another; and
// the seed's walk walks there, judged over seeds (tests/README.md). Seed 1, walking forward 20 s
// in the seed world: the seed's walk covers 1.76 m standing, while the firmware's closed-loop
// defaults (tuned for the faithful world) fall after 0.80 m (tests/bench/RESULTS.md; not
// asserted, a known limit of those defaults in that world).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "run_command.hpp"
#include "seeds.hpp"
#include "temp_dir.hpp"

namespace stride::sim {
namespace {

const std::string kStride = std::string(STRIDE_BIN_DIR) + "/stride sim ";
const std::string kSeedWalk = STRIDE_SOURCE_DIR "/firmware/config/seed-walk.json";

nlohmann::json sim_json(const std::string& args) {
  int code = -1;
  const std::string out = test::run_command(kStride + args + " --json", code);
  EXPECT_EQ(code, 0) << args << ": " << out;
  return out.empty() ? nlohmann::json::object() : nlohmann::json::parse(out);
}

TEST(StrideSimSeedWorld, WalksTheSeedsWalkUnlessParamsSaysOtherwise) {
  test::TempDir dir;
  const std::string defaults = (dir.path() / "none.json").string();
  std::ofstream(defaults) << "{}\n";  // no parameter changed: the firmware's defaults
  // Which parameters the episode ran with: the same episode as with the file given, another
  // with the firmware's defaults.
  const std::string walk = "walk --vx 1 --duration 4 --world seed";
  const nlohmann::json seed = sim_json(walk);
  EXPECT_EQ(seed.at("state_hash"), sim_json(walk + " --params " + kSeedWalk).at("state_hash"));
  EXPECT_NE(seed.at("state_hash"), sim_json(walk + " --params " + defaults).at("state_hash"));
  // The faithful world (the default) keeps the firmware's defaults.
  EXPECT_EQ(sim_json("walk --vx 1 --duration 2").at("state_hash"),
            sim_json("walk --vx 1 --duration 2 --params " + defaults).at("state_hash"));
}

// The seed's walk walks forward in the seed world: 10 s on seeds 1-5, without a fall (counted
// with one to spare) and the median distance. Measured 2026-11-28, seeds 1-20: median 0.654 m, IQR
// 0.008 m (0.644-0.666), no fall in 20.
TEST(StrideSimSeedWorld, TheSeedsWalkWalksForwardOnSeeds) {
  int upright = 0;
  const test::Figures distance =
      test::Seeds(5).run("distance in 10 s [m]", [&](std::uint64_t seed) {
        const nlohmann::json r =
            sim_json("walk --vx 1 --duration 10 --world seed --seed " + std::to_string(seed));
        upright += r.at("fell").get<bool>() ? 0 : 1;
        return r.at("distance_m").get<double>();
      });
  EXPECT_GE(upright, static_cast<int>(distance.size()) - 1);
  EXPECT_GT(distance.median(), 0.55);  // 0.654 m, IQR 0.008 (seeds 1-20)
}

}  // namespace
}  // namespace stride::sim
