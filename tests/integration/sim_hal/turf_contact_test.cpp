// Integration tests (release build): the turf contact (ContactOptions::turf(), `--contact turf`,
// issue 29 point 1) on both engines: the standing robot sinks as deep on each, the 5 mm layer
// over solid ground holds it about 15 mm lower than the seed's 2 cm grass does, and a bad
// --contact is one line and exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "run_command.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace stride::sim {
namespace {

/// Torso height after standing 3 s in the Stand pose (identified servo, no noise) [m].
double standing_height(EngineKind engine, const ContactOptions& contact) {
  WorldOptions options;
  options.engine = engine;
  options.contact = contact;
  options.servo.law = ServoLaw::kIdentified;
  std::unique_ptr<SimWorld> world;
  EXPECT_TRUE(SimWorld::create(options, world));
  SimRobot robot(std::move(world));
  EpisodeOptions episode;
  episode.duration_s = 3.0;
  const EpisodeResult r = run_episode(robot, hold_pose_controller(igus_stand_pose()), episode);
  EXPECT_FALSE(r.fell);
  return robot.world().torso_pose().translation().z();
}

TEST(TurfContact, TheRobotStandsAsDeepOnBothEnginesAndLowerThanOnTheSeedGrass) {
  const double simbody = standing_height(EngineKind::kSimbody, ContactOptions::turf());
  const double mujoco = standing_height(EngineKind::kMujoco, ContactOptions::turf());
  const double seed = standing_height(EngineKind::kSimbody, ContactOptions::seed());
  std::printf("torso height on turf: Simbody %.5f m, MuJoCo %.5f m; seed grass (Simbody) %.5f m\n",
              simbody, mujoco, seed);
  EXPECT_NEAR(simbody, mujoco, 0.5e-3);
  // The grass top is 15 mm lower; the studs sink a little less (they reach the solid ground).
  EXPECT_GT(seed - simbody, 0.0140);
  EXPECT_LT(seed - simbody, 0.0155);
}

TEST(TurfContact, ABadContactIsOneLineAndExitTwo) {
  int code = -1;
  const std::string err = stride::test::run_command(
      std::string(STRIDE_BIN_DIR) + "/stride sim stand --contact lawn 2>&1 >/dev/null", code);
  EXPECT_EQ(code, 2);
  EXPECT_NE(err.find("--contact"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

}  // namespace
}  // namespace stride::sim
