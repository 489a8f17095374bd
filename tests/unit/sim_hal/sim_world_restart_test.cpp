// SimWorld::create(options, spec) and SimWorld::restart: one world per worker, made once and
// restarted for every episode, must give the bits of a new world made and reset as before
// (create(options) then reset(spec)), on both engines, with randomisation and sensor noise.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"
#include "sway_episode.hpp"

namespace stride::sim {
namespace {

/// A randomised, noisy world (every per-reset draw in use) on `engine`.
WorldOptions randomised(EngineKind engine, std::uint64_t seed, bool chain_imu) {
  WorldOptions o;
  o.engine = engine;
  o.seed = seed;
  o.imu.set_noise(true);
  if (!chain_imu) o.imu.chain = ImuChain::ideal();  // the plain sampler draws its own noise
  o.randomise = {0.2, 0.05, 0.1, 0.5};
  o.randomise.contact_range = 0.5;  // the ground drawn too (one more draw)
  o.randomise.com_range = 0.01;     // and the trunk's centre of mass (two more)
  // and the servos and the supply (three more, issue 54)
  o.randomise.servo_friction_min = 0.8;
  o.randomise.servo_friction_max = 1.6;
  o.randomise.servo_torque_min = 0.8;
  o.randomise.servo_torque_max = 1.05;
  o.randomise.supply_min_v = 12.0;
  o.randomise.supply_max_v = 16.8;
  return o;
}

/// The reset of a task: the Stand pose with a ball further out.
ResetSpec task_spec() {
  ResetSpec spec = ResetSpec::standing();
  spec.ball_position.x() = 0.5;
  return spec;
}

std::pair<std::uint64_t, double> sway(std::unique_ptr<SimWorld> world) {
  return test::sway(std::move(world), 40);
}

/// The way worlds were made before: create() (its start-up reset) and the task's reset.
std::unique_ptr<SimWorld> create_then_reset(const WorldOptions& options) {
  std::unique_ptr<SimWorld> world;
  EXPECT_TRUE(SimWorld::create(options, world));
  EXPECT_TRUE(world->reset(task_spec()));
  return world;
}

class Restart : public ::testing::TestWithParam<std::pair<EngineKind, bool>> {};

TEST_P(Restart, CreateWithASpecGivesTheBitsOfCreateThenReset) {
  const auto [engine, chain] = GetParam();
  const WorldOptions options = randomised(engine, 11, chain);
  const auto before = sway(create_then_reset(options));
  std::unique_ptr<SimWorld> world;
  ASSERT_TRUE(SimWorld::create(options, task_spec(), world));
  const auto now = sway(std::move(world));
  EXPECT_EQ(now.first, before.first);
  EXPECT_EQ(now.second, before.second);
}

TEST_P(Restart, ARestartedWorldGivesTheBitsOfANewOne) {
  const auto [engine, chain] = GetParam();
  // A world that has run an episode with other draws (another seed) and then a failed one.
  std::unique_ptr<SimWorld> world;
  ASSERT_TRUE(SimWorld::create(randomised(engine, 5, chain), task_spec(), world));
  SimRobot used(std::move(world));
  used.sleep_until(30);
  used.world().set_joint_speed(3, 1e6);  // explodes on the next step
  used.sleep_until(31);
  ASSERT_NE(used.world().status(), WorldStatus::kRunning);
  world = used.release_world();
  for (const std::uint64_t seed : {11u, 12u}) {
    const WorldOptions options = randomised(engine, seed, chain);
    const auto fresh = sway(create_then_reset(options));
    ASSERT_TRUE(world->restart(options, task_spec()));
    SimRobot robot(std::move(world));
    const auto restarted = sway(robot.release_world());
    EXPECT_EQ(restarted.first, fresh.first) << "seed " << seed;
    EXPECT_EQ(restarted.second, fresh.second) << "seed " << seed;
    ASSERT_TRUE(SimWorld::create(options, task_spec(), world));  // for the next round
  }
}

TEST(Restart, ABadOptionIsAnErrorNamingIt) {
  std::unique_ptr<SimWorld> world;
  ASSERT_TRUE(SimWorld::create(WorldOptions{}, ResetSpec::standing(), world));
  WorldOptions bad;
  bad.battery_voltage_v = -1.0;
  const Status s = world->restart(bad, ResetSpec::standing());
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("battery voltage"), std::string::npos) << s.message();
}

std::string restart_case_name(const ::testing::TestParamInfo<std::pair<EngineKind, bool>>& param) {
  return std::string(to_string(param.param.first)) + (param.param.second ? "Cm730Imu" : "PlainImu");
}

INSTANTIATE_TEST_SUITE_P(EnginesAndImus, Restart,
                         ::testing::Values(std::pair{EngineKind::kSimbody, true},
                                           std::pair{EngineKind::kSimbody, false},
                                           std::pair{EngineKind::kMujoco, true},
                                           std::pair{EngineKind::kMujoco, false}),
                         restart_case_name);

}  // namespace
}  // namespace stride::sim
