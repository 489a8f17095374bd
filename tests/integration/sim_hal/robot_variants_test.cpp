// Robot variants per reset (Randomisation::com_range, issue 41 point 4): the trunk's centre of
// mass moved within +-range in x and y at each reset, reproducible from the seed, on both
// engines, and acting exactly as the same offset given as the robot's calibration does.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {
namespace {

/// The firmware standing 2 s in `world`; the state hash at the end.
std::uint64_t stand(std::unique_ptr<SimWorld> world) {
  std::unique_ptr<fw::Firmware> firmware;
  EXPECT_TRUE(fw::Firmware::create({}, firmware));
  SimRobot robot(std::move(world));
  EpisodeOptions episode;
  episode.duration_s = 2.0;
  fw::Controller& controller = firmware->controller();
  const EpisodeResult r = run_episode(
      robot, [&](const hal::SensorFrame& in, hal::Tick tick) { return controller.step(in, tick); },
      episode);
  EXPECT_FALSE(r.fell);
  return r.state_hash;
}

WorldOptions varied(EngineKind engine, std::uint64_t seed) {
  WorldOptions o;
  o.engine = engine;
  o.seed = seed;
  o.control_period_ns = 10'000'000;
  o.randomise.com_range = 0.01;
  return o;
}

TEST(RobotVariants, TheTrunksCentreOfMassMovesPerResetWithinTheRangeFromTheSeed) {
  for (const EngineKind engine : {EngineKind::kSimbody, EngineKind::kMujoco}) {
    auto shifts = [&](std::uint64_t seed) {
      std::unique_ptr<SimWorld> world;
      EXPECT_TRUE(SimWorld::create(varied(engine, seed), world));
      std::vector<Eigen::Vector3d> out = {world->trunk_com_shift()};
      for (int i = 0; i < 3; ++i) {
        EXPECT_TRUE(world->reset(ResetSpec::standing()));
        out.push_back(world->trunk_com_shift());
      }
      return out;
    };
    const auto a = shifts(5), b = shifts(5), c = shifts(6);
    EXPECT_EQ(a, b) << to_string(engine);
    EXPECT_NE(a, c) << to_string(engine);
    EXPECT_NE(a[0], a[1]) << to_string(engine);
    for (const Eigen::Vector3d& s : a) {
      EXPECT_LE(std::abs(s.x()), 0.01);
      EXPECT_LE(std::abs(s.y()), 0.01);
      EXPECT_EQ(s.z(), 0.0);
      EXPECT_GT(s.head<2>().norm(), 0.0);
    }
    // Nothing drawn without the range.
    WorldOptions plain = varied(engine, 5);
    plain.randomise.com_range = 0.0;
    std::unique_ptr<SimWorld> world;
    ASSERT_TRUE(SimWorld::create(plain, world));
    EXPECT_EQ(world->trunk_com_shift(), Eigen::Vector3d::Zero());
  }
}

TEST(RobotVariants, ADrawnShiftActsAsTheSameOffsetInTheRobotsCalibration) {
  for (const EngineKind engine : {EngineKind::kSimbody, EngineKind::kMujoco}) {
    std::unique_ptr<SimWorld> drawn;
    ASSERT_TRUE(SimWorld::create(varied(engine, 7), drawn));
    const Eigen::Vector3d shift = drawn->trunk_com_shift();
    WorldOptions calibrated = varied(engine, 7);
    calibrated.randomise.com_range = 0.0;
    calibrated.robot.trunk_com_offset_m = shift.head<2>();
    std::unique_ptr<SimWorld> same;
    ASSERT_TRUE(SimWorld::create(calibrated, same));
    WorldOptions nominal = calibrated;
    nominal.robot.trunk_com_offset_m.setZero();
    std::unique_ptr<SimWorld> plain;
    ASSERT_TRUE(SimWorld::create(nominal, plain));
    const std::uint64_t a = stand(std::move(drawn)), b = stand(std::move(same)),
                        c = stand(std::move(plain));
    EXPECT_EQ(a, b) << to_string(engine);
    EXPECT_NE(a, c) << to_string(engine);
  }
}

TEST(RobotVariants, ARangeBeyondFiveCentimetresIsRefusedNamingIt) {
  WorldOptions o = varied(EngineKind::kSimbody, 1);
  o.randomise.com_range = 0.2;
  std::unique_ptr<SimWorld> world;
  const Status s = SimWorld::create(o, world);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("com_range"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace stride::sim
