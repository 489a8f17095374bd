// Tests of the Simbody world: contact, servos in the multibody, IMU, failures, determinism.
#include <gtest/gtest.h>

#include <cmath>

#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"
#include "sway_episode.hpp"

namespace stride::sim {
namespace {

std::unique_ptr<SimWorld> make_world(WorldOptions options = {}) {
  std::unique_ptr<SimWorld> world;
  const Status s = SimWorld::create(options, world);
  EXPECT_TRUE(s) << s.message();
  return world;
}

void hold(SimWorld& world, const std::array<double, hal::kServoCount>& pose, double p_gain = 76) {
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    hal::ServoCommand c;
    c.position_rad = pose[i];
    c.p_gain = p_gain;
    c.torque_enable = true;
    world.set_servo_command(i, c);
  }
}

TEST(SimWorld, DroppedBallSettlesOnTheGrassLayer) {
  WorldOptions options;
  auto world = make_world(options);
  ResetSpec spec = ResetSpec::standing();
  spec.ball_position = {2.0, 0.0, 0.5};  // far from the robot, dropped from 0.5 m
  ASSERT_TRUE(world->reset(spec));
  hold(*world, igus_stand_pose());
  for (int k = 0; k < 200; ++k) ASSERT_TRUE(world->advance_period());  // 2 s
  const GroundTruth g = world->ground_truth();
  // Resting on the grass spring: centre at grass top + radius - m g / k.
  const ContactOptions& c = options.contact;
  const double expected = c.grass_thickness_m + options.ball.radius_m -
                          options.ball.mass_kg * options.gravity_mps2 / c.grass_stiffness_n_m;
  EXPECT_NEAR(g.ball_position.z(), expected, 2e-4);
  EXPECT_GT(g.ball_position.z(), c.grass_thickness_m);  // above the solid ground: on the grass
  EXPECT_LT(g.ball_velocity.norm(), 1e-3);
  EXPECT_NEAR(g.ball_position.x(), 2.0, 1e-3);
}

TEST(SimWorld, RobotStandsOnItsStudsAndTheImuReadsGravity) {
  auto world = make_world();
  hold(*world, igus_stand_pose());
  for (int k = 0; k < 300; ++k) ASSERT_TRUE(world->advance_period());  // 3 s
  const GroundTruth g = world->ground_truth();
  EXPECT_EQ(g.left_contact.points_in_contact, 4);  // the four studs, not the sole
  EXPECT_EQ(g.right_contact.points_in_contact, 4);
  EXPECT_EQ(g.other_contacts, 0);
  const double weight = world->model().total_mass() * 9.81;
  EXPECT_NEAR(g.left_contact.force.z() + g.right_contact.force.z(), weight,
              0.05 * weight);               // a small residual sway remains
  EXPECT_GT(g.torso.linear()(2, 2), 0.95);  // upright
  // Standing CoM height above the flat sole: 0.424 m with straight legs (igus.md 1.2); the
  // Stand pose bends the knees slightly. The soles are level and clear of the grass top
  // (the studs carry the robot), the studs sunk a few millimetres into the grass.
  const double sole =
      0.5 * (g.left_foot.translation().z() + g.right_foot.translation().z()) - 0.0383;
  const double top = world->options().contact.grass_thickness_m;  // turf: 5 mm
  EXPECT_NEAR(g.center_of_mass.z() - sole, 0.42, 0.01);
  EXPECT_GT(sole, top);
  EXPECT_LT(sole, top + 0.018);
  EXPECT_GT(g.left_foot.linear()(2, 2), 0.999);
  const ImuReading& imu = world->imu();  // noise off by default
  EXPECT_NEAR(imu.accel.norm(), 9.81, 0.3);
  EXPECT_GT(imu.accel.z(), 9.0);
  EXPECT_LT(imu.gyro.norm(), 0.15);
}

TEST(SimWorld, ServoStepResponseFollowsItsModel) {
  auto world = make_world();
  std::array<double, hal::kServoCount> pose = igus_stand_pose();
  hold(*world, pose);
  for (int k = 0; k < 20; ++k) ASSERT_TRUE(world->advance_period());
  // Head yaw (servo 19, vertical axis: no gravity load): a 0.6 rad step at full speed.
  constexpr std::size_t kHeadYaw = 18;
  pose[kHeadYaw] = 0.6;
  hold(*world, pose, 254);
  const double no_load = motor_curve(fw::ServoModel::kMx64, 14.8).no_load_speed_rad_s;
  double max_speed = 0.0;
  double t_half = -1;
  for (int k = 1; k <= 100; ++k) {
    ASSERT_TRUE(world->advance_period());
    const hal::ServoState s = world->servo_state(kHeadYaw);
    max_speed = std::max(max_speed, std::abs(s.speed_rad_s));
    if (t_half < 0 && s.position_rad > 0.3) t_half = k * 0.01;
  }
  EXPECT_LE(max_speed, no_load + 0.02);     // never faster than the motor's no-load speed
  EXPECT_GE(t_half, 0.3 / no_load - 0.01);  // so half the move takes at least this long
  EXPECT_LT(t_half, 0.3);                   // but it does move
  EXPECT_NEAR(world->servo_state(kHeadYaw).position_rad, 0.6, 0.01);  // settled (stiff P 254)
  // Moving speed 1 rad/s: a ramp back to 0.
  hal::ServoCommand c;
  c.position_rad = 0.0;
  c.moving_speed_rad_s = 1.0;
  c.p_gain = 254;
  c.torque_enable = true;
  world->set_servo_command(kHeadYaw, c);
  for (int k = 0; k < 30; ++k) ASSERT_TRUE(world->advance_period());  // 0.3 s
  EXPECT_NEAR(world->servo_joint_angle(kHeadYaw), 0.3, 0.03);
}

TEST(SimWorld, TorqueSaturationAndJointLimitsHold) {
  // Pins the seed's servo law (ServoModel), whose load register reads the clipped torque; the
  // identified law's reads the duty (back-EMF lowers it while the servo moves).
  auto world = make_world(WorldOptions::seed_world());
  std::array<double, hal::kServoCount> pose = igus_stand_pose();
  hold(*world, pose);
  for (int k = 0; k < 20; ++k) ASSERT_TRUE(world->advance_period());
  // Head pitch far beyond its upper limit (1.5708) at the highest gain.
  constexpr std::size_t kHeadPitch = 19;
  pose[kHeadPitch] = 3.0;
  hold(*world, pose, 254);
  // Elbow with a torque limit of 20 %: the load never exceeds it.
  hal::ServoCommand elbow;
  elbow.position_rad = 0.0;
  elbow.p_gain = 254;
  elbow.torque_limit = 0.2;
  elbow.torque_enable = true;
  world->set_servo_command(4, elbow);
  double max_pitch = -10, max_load = 0;
  for (int k = 0; k < 150; ++k) {
    ASSERT_TRUE(world->advance_period());
    max_pitch = std::max(max_pitch, world->servo_joint_angle(kHeadPitch));
    max_load = std::max(max_load, std::abs(world->servo_state(4).load));
  }
  const JointSpec& joint =
      world->model().joints()[static_cast<std::size_t>(world->model().joint_index("head_pitch"))];
  EXPECT_LT(max_pitch, joint.upper + 0.03);
  EXPECT_GT(max_pitch, joint.upper - 0.01);
  EXPECT_LE(max_load, 0.2 + 1e-9);
  EXPECT_GT(max_load, 0.19);  // it did saturate
}

TEST(SimWorld, ExplodingStateEndsWithAStatusNotACrash) {
  WorldOptions options;
  options.physics_step_ns = 10'000'000;  // far too coarse for the stiff servos
  auto world = make_world(options);
  hold(*world, igus_stand_pose(), 254);
  bool running = true;
  for (int k = 0; k < 500 && running; ++k) running = world->advance_period();
  EXPECT_FALSE(running);
  EXPECT_NE(world->status(), WorldStatus::kRunning);
  EXPECT_FALSE(world->failure_reason().empty());
  const double t = world->time_s();
  EXPECT_FALSE(world->advance_period());  // frozen, still answering
  EXPECT_EQ(world->time_s(), t);
  // A NaN pushed into the state is caught too.
  auto other = make_world();
  other->set_joint_speed(0, std::numeric_limits<double>::quiet_NaN());
  EXPECT_FALSE(other->advance_period());
  EXPECT_EQ(other->status(), WorldStatus::kNonFinite);
  EXPECT_NE(other->failure_reason().find("non-finite"), std::string::npos);
}

TEST(SimWorld, SameSeedGivesBitIdenticalStatesAndOtherSeedsDiffer) {
  WorldOptions options;
  options.imu.set_noise(true);
  options.randomise = {0.2, 0.05, 0.1, 0.5};
  auto run = [&](std::uint64_t seed) {
    options.seed = seed;
    return test::sway(make_world(options), 50);
  };
  const auto a = run(7), b = run(7), c = run(8);
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second, b.second);
  EXPECT_NE(a.first, c.first);
  EXPECT_NE(a.second, c.second);
}

TEST(SimRobot, LockstepTicksAndSerialLikeFrames) {
  auto world = make_world();
  SimRobot robot(std::move(world));
  EXPECT_EQ(robot.period_ns(), 10'000'000);
  EXPECT_EQ(robot.sleep_until(7), 7);
  EXPECT_NEAR(robot.world().time_s(), 0.07, 1e-12);
  EXPECT_EQ(robot.sleep_until(3), 7);  // the past: returns at once
  hal::SensorFrame frame;
  robot.read(frame);
  EXPECT_EQ(frame.tick, 7);
  for (const hal::ServoState& s : frame.servos) {
    EXPECT_EQ(s.health, hal::DeviceHealth::kOk);
    const double ticks = s.position_rad / kEncoderRadPerTick;
    EXPECT_NEAR(ticks, std::round(ticks), 1e-6);  // quantised to the encoder
    EXPECT_NEAR(s.voltage_v, 14.8, 1e-12);
  }
  EXPECT_EQ(frame.cm730.health, hal::DeviceHealth::kOk);
  EXPECT_NEAR(frame.cm730.voltage_v, 14.8, 1e-12);
  hal::CommandFrame commands;
  commands.servos[3].position_rad = 0.5;
  commands.servos[3].p_gain = 40;
  commands.servos[3].torque_enable = true;
  robot.write(commands);
  robot.read(frame);
  EXPECT_EQ(frame.servos[3].goal_position_rad, 0.5);
  EXPECT_EQ(frame.servos[3].p_gain, 40);
  robot.set_torque_enable(false);
  robot.read(frame);
  EXPECT_FALSE(frame.servos[3].torque_enabled);
}

TEST(SimWorld, RejectsBadOptions) {
  std::unique_ptr<SimWorld> world;
  WorldOptions options;
  options.physics_step_ns = 3'000'000;  // does not divide 10 ms
  Status s = SimWorld::create(options, world);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("divide"), std::string::npos);
  options = {};
  options.urdf = "/nonexistent.urdf";
  s = SimWorld::create(options, world);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("/nonexistent.urdf"), std::string::npos);
  options = {};
  options.servo_joints[4] = "no_such_joint";
  s = SimWorld::create(options, world);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("no_such_joint"), std::string::npos);
}

}  // namespace
}  // namespace stride::sim

namespace stride::sim {
namespace {

TEST(SimWorld, APreloadedModelBuildsTheSameWorldWithoutReadingTheUrdf) {
  auto model = std::make_shared<RobotModel>();
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), *model));
  auto run = [](const WorldOptions& options) {
    std::unique_ptr<SimWorld> world;
    const Status s = SimWorld::create(options, world);
    EXPECT_TRUE(s) << s.message();
    if (!world) return std::uint64_t{0};
    for (int k = 0; k < 20; ++k) EXPECT_TRUE(world->advance_period());
    return world->state_hash();
  };
  WorldOptions from_file;
  WorldOptions preloaded;
  preloaded.model = model;
  preloaded.urdf = "/nonexistent/robot.urdf";  // never read: the model is given
  EXPECT_EQ(run(from_file), run(preloaded));
  // Without a model the path is read, and a missing file is an error naming it.
  preloaded.model = nullptr;
  std::unique_ptr<SimWorld> world;
  const Status missing = SimWorld::create(preloaded, world);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.message().find("/nonexistent/robot.urdf"), std::string::npos);
}

}  // namespace
}  // namespace stride::sim
