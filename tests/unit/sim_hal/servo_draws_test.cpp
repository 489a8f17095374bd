// The robot as it may be (issue 54 point 2): Randomisation's servo friction, servo torque and
// supply draws. Each is drawn once per reset inside its bounds; equal bounds draw nothing and
// give the world a fixed robot exactly as the world file's calibration does; bad bounds are
// refused naming the pair.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "stride/sim_hal/sim_world.hpp"
#include "sway_episode.hpp"

namespace stride::sim {
namespace {

constexpr int kPeriods = 40;

std::uint64_t sway_hash(const WorldOptions& options) {
  std::unique_ptr<SimWorld> world;
  EXPECT_TRUE(SimWorld::create(options, ResetSpec::standing(), world));
  return test::sway(std::move(world), kPeriods).first;
}

TEST(ServoDraws, TheSupplyIsDrawnPerResetInsideItsBounds) {
  WorldOptions o;
  o.randomise.supply_min_v = 12.0;
  o.randomise.supply_max_v = 16.8;
  double lowest = 100.0, highest = 0.0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    o.seed = seed;
    std::unique_ptr<SimWorld> world;
    ASSERT_TRUE(SimWorld::create(o, ResetSpec::standing(), world));
    const double v = world->battery_voltage();
    EXPECT_GE(v, 12.0);
    EXPECT_LE(v, 16.8);
    EXPECT_EQ(world->servo_state(0).voltage_v, v);  // what the servos report
    lowest = std::min(lowest, v);
    highest = std::max(highest, v);
  }
  // 30 uniform draws span most of the 4.8 V (each end within 1 V: chance 2 x 0.79^30 = 0.2 %).
  EXPECT_LT(lowest, 13.0);
  EXPECT_GT(highest, 15.8);
}

TEST(ServoDraws, EqualBoundsAreTheCalibrationsFixedRobot) {
  for (const EngineKind engine : {EngineKind::kSimbody, EngineKind::kMujoco}) {
    SCOPED_TRACE(to_string(engine));
    WorldOptions drawn, calibrated;
    drawn.engine = calibrated.engine = engine;
    drawn.randomise.servo_friction_min = drawn.randomise.servo_friction_max = 1.5;
    drawn.randomise.servo_torque_min = drawn.randomise.servo_torque_max = 0.85;
    drawn.randomise.supply_min_v = drawn.randomise.supply_max_v = 12.5;
    calibrated.robot.friction_scale = 1.5;
    calibrated.robot.torque_scale_mx64 = calibrated.robot.torque_scale_mx106 = 0.85;
    calibrated.battery_voltage_v = 12.5;
    EXPECT_EQ(sway_hash(drawn), sway_hash(calibrated));
    WorldOptions nominal;
    nominal.engine = engine;
    EXPECT_NE(sway_hash(drawn), sway_hash(nominal));  // it acts
  }
}

TEST(ServoDraws, ADrawnScaleActsAndDiffersBySeed) {
  WorldOptions o;
  o.randomise.servo_friction_min = 0.8;
  o.randomise.servo_friction_max = 1.6;
  o.seed = 3;
  const std::uint64_t three = sway_hash(o);
  o.seed = 4;
  EXPECT_NE(sway_hash(o), three);
  // Without the draw, seeds 3 and 4 of this noise-free world are the same world.
  WorldOptions plain;
  plain.seed = 3;
  const std::uint64_t plain_three = sway_hash(plain);
  plain.seed = 4;
  EXPECT_EQ(sway_hash(plain), plain_three);
}

TEST(ServoDraws, BadBoundsAreRefusedNamingThePair) {
  WorldOptions o;
  o.randomise.servo_friction_min = 1.6;
  o.randomise.servo_friction_max = 0.8;
  std::unique_ptr<SimWorld> world;
  Status s = SimWorld::create(o, world);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("servo_friction_min and _max"), std::string::npos) << s.message();
  o = WorldOptions{};
  o.randomise.supply_max_v = 16.8;  // no lower bound
  s = SimWorld::create(o, world);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("supply_min and _max"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace stride::sim
