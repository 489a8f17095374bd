// Tests of the MuJoCo engine's "build once" (issue 42 point 1): an episode's randomised masses,
// trunk centre of mass, friction and grass thickness written into the compiled model of the
// nominal MJCF give the compiler's model of the episode's own MJCF bit for bit, whatever came
// before; a randomised reset compiles nothing; a value the compiler treats otherwise compiles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <mujoco/mjxmacro.h>

#include "engine_test_models.hpp"
#include "mujoco/mujoco_engine.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {
namespace {

/// The first field in which two compiled models differ ("" if none): every array of mjModel
/// (MuJoCo's X macros), its sizes, options and statistics, byte for byte.
std::string first_difference(const mjModel* a, const mjModel* b) {
#define X(name) \
  if (a->name != b->name) return #name;
  MJMODEL_INTS
#undef X
  const mjModel* m = a;
  MJMODEL_POINTERS_PREAMBLE(m)
  (void)nuser_body, (void)nuser_jnt, (void)nuser_geom, (void)nuser_site, (void)nuser_cam;
  (void)nuser_tendon, (void)nuser_actuator, (void)nuser_sensor, (void)nq, (void)nv, (void)na;
  (void)nu, (void)nmocap;
#define X(type, name, nr, nc)                                                                  \
  if (std::memcmp(                                                                             \
          a->name, b->name,                                                                    \
          sizeof(type) * static_cast<std::size_t>(a->nr) * static_cast<std::size_t>(nc)) != 0) \
    return #name;
  MJMODEL_POINTERS
#undef X
  if (std::memcmp(&a->opt, &b->opt, sizeof a->opt) != 0) return "opt";
  if (std::memcmp(&a->stat, &b->stat, sizeof a->stat) != 0) return "stat";
  return "";
}

EngineModel turf_model(const RobotModel& robot) {
  EngineModel m = engine_test::neutral_model(robot);
  m.left_foot = robot.link_index("left_foot_link");
  m.right_foot = robot.link_index("right_foot_link");
  m.ball.present = true;                   // the ball-robot pairs
  m.contact = ContactOptions::turf();      // the solid ground and its pairs
  m.contact.grass_stiffness_n_m = 1800.0;  // not in the MJCF
  for (std::size_t j = 0; j < robot.joints().size(); ++j) m.joint_armature[j] = 0.002;
  return m;
}

/// `base` with every value drawn per reset changed (as SimWorld's randomisation does).
EngineModel drawn(const EngineModel& base, double phase) {
  EngineModel m = base;
  for (std::size_t l = 0; l < m.link_mass_scale.size(); ++l)
    m.link_mass_scale[l] = 1.0 + 0.05 * std::sin(phase + 1.7 * static_cast<double>(l));
  m.root_com_shift = Eigen::Vector3d(0.01 * std::cos(phase), -0.013 * std::sin(phase), 0.0);
  m.friction = 0.8 + 0.1 * std::sin(phase);
  m.contact.grass_thickness_m = 0.004 + 0.002 * std::cos(phase);
  return m;
}

/// The old path's model of `model`: its own MJCF compiled by a new engine.
std::unique_ptr<PhysicsEngine> compiled(const EngineModel& model) {
  auto engine = make_mujoco_engine();
  mujoco_set_always_compile(true);
  const Status s = engine->build(model);
  mujoco_set_always_compile(false);
  EXPECT_TRUE(s) << s.message();
  return engine;
}

TEST(MujocoEpisodeValues, APatchedModelIsTheCompilersBitForBit) {
  RobotModel robot;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), robot));
  const EngineModel base = turf_model(robot);
  auto engine = make_mujoco_engine();
  ASSERT_TRUE(engine->build(base));
  const std::int64_t compiles = mujoco_compile_count();
  // Episodes in any order, the same one twice: each model is its own text's compiled model.
  for (const double phase : {0.3, 2.0, -1.1, 0.3, 5.0}) {
    const EngineModel model = drawn(base, phase);
    ASSERT_TRUE(engine->build(model));
    const auto reference = compiled(model);
    EXPECT_EQ(first_difference(mujoco_model_of(*engine), mujoco_model_of(*reference)), "")
        << "phase " << phase;
    const mjModel* m = mujoco_model_of(*engine);
    EXPECT_EQ(m->body_mass[mj_name2id(m, mjOBJ_BODY, "l1")],
              model.link_mass_scale[1] * robot.links()[1].mass);
  }
  ASSERT_TRUE(engine->build(base));
  EXPECT_EQ(first_difference(mujoco_model_of(*engine), mujoco_model_of(*compiled(base))), "");
  EXPECT_EQ(mujoco_compile_count(), compiles + 6);  // the references only
}

/// A 300-step drop of the robot beside the ball on `engine` after build(model).
std::uint64_t drop(PhysicsEngine& engine, const EngineModel& model) {
  EXPECT_TRUE(engine.build(model));
  const std::size_t joints = model.robot->joints().size();
  EngineStart start;
  start.joint_angles.assign(joints, 0.0);
  start.torso_position = Eigen::Vector3d(0, 0, 0.45);
  start.ball_position = Eigen::Vector3d(0.2, 0.0, 0.2);
  start.ball_velocity = Eigen::Vector3d(-1.0, 0.0, 0.0);
  EXPECT_TRUE(engine.start(start));
  std::vector<double> torque(joints, 0.0);
  std::string reason;
  for (int k = 0; k < 300; ++k) {
    for (std::size_t j = 0; j < joints; ++j)
      torque[j] = -3.0 * engine.joint_angle(j) - 0.05 * engine.joint_speed(j);
    EXPECT_EQ(engine.step(torque, reason), WorldStatus::kRunning) << reason;
  }
  return engine.hash(14695981039346656037ULL);
}

TEST(MujocoEpisodeValues, AValueTheCompilerTreatsOtherwiseCompilesItsOwnText) {
  RobotModel robot;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), robot));
  const EngineModel base = turf_model(robot);
  // The grass plane at the world's origin: the compiler marks its frame as the world's
  // (geom_sameframe), which a written position would not change.
  EngineModel flat = drawn(base, 1.0);
  flat.contact.grass_thickness_m = 0.0;
  const std::uint64_t reference = drop(*compiled(flat), flat);
  auto engine = make_mujoco_engine();
  const std::uint64_t before_base = drop(*engine, base);
  std::int64_t compiles = mujoco_compile_count();
  EXPECT_EQ(drop(*engine, flat), reference);
  EXPECT_EQ(mujoco_compile_count(), compiles + 1);
  EXPECT_EQ(drop(*engine, flat), reference);  // its own text again: kept
  EXPECT_EQ(mujoco_compile_count(), compiles + 1);
  EXPECT_EQ(drop(*engine, base), before_base);  // the nominal model compiled again
  EXPECT_EQ(mujoco_compile_count(), compiles + 2);
  compiles = mujoco_compile_count();
  EXPECT_EQ(drop(*engine, drawn(base, 2.5)), drop(*compiled(drawn(base, 2.5)), drawn(base, 2.5)));
  EXPECT_EQ(mujoco_compile_count(), compiles + 1);  // the reference's
}

/// A randomised, noisy MuJoCo world: every per-reset draw in use.
WorldOptions randomised(std::uint64_t seed) {
  WorldOptions o;
  o.engine = EngineKind::kMujoco;
  o.seed = seed;
  o.imu.set_noise(true);
  o.randomise = {0.2, 0.05, 0.1, 0.5};
  o.randomise.contact_range = 0.5;
  o.randomise.com_range = 0.01;
  return o;
}

/// The state hash after the Stand pose is held 0.6 s from `world`'s current reset.
std::uint64_t stand(SimWorld& world) {
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    hal::ServoCommand c;
    c.position_rad = igus_stand_pose()[i];
    c.p_gain = 32;
    c.torque_enable = true;
    world.set_servo_command(i, c);
  }
  for (int k = 0; k < 60; ++k) EXPECT_TRUE(world.advance_period());
  return world.state_hash();
}

std::uint64_t restarted(SimWorld& world, const WorldOptions& options) {
  EXPECT_TRUE(world.restart(options, ResetSpec::standing()));
  return stand(world);
}

std::uint64_t fresh(const WorldOptions& options) {
  std::unique_ptr<SimWorld> world;
  EXPECT_TRUE(SimWorld::create(options, ResetSpec::standing(), world));
  return stand(*world);
}

TEST(MujocoEpisodeValues, SameSeedSameBitsWhateverTheOrderAndNoCompileAfterTheFirst) {
  const WorldOptions a = randomised(3), b = randomised(4);
  std::unique_ptr<SimWorld> world;
  ASSERT_TRUE(SimWorld::create(a, world));
  const std::int64_t compiles = mujoco_compile_count();
  const std::uint64_t a1 = restarted(*world, a);
  const std::uint64_t b1 = restarted(*world, b);
  const std::uint64_t a2 = restarted(*world, a);
  std::vector<std::uint64_t> resets;  // more randomised resets of one world
  for (int e = 0; e < 3; ++e) {
    ASSERT_TRUE(world->reset(ResetSpec::standing()));
    resets.push_back(stand(*world));
  }
  EXPECT_EQ(mujoco_compile_count(), compiles);  // randomised resets compile nothing
  EXPECT_NE(a1, b1);
  EXPECT_EQ(a1, a2);
  EXPECT_EQ(fresh(b), b1);  // a new world for B: the restarted one's bits
  EXPECT_EQ(fresh(a), a1);
  // The old path (every reset compiles its own text) gives the same bits.
  mujoco_set_always_compile(true);
  EXPECT_EQ(fresh(b), b1);
  ASSERT_TRUE(SimWorld::create(a, world));
  EXPECT_EQ(restarted(*world, a), a1);
  for (int e = 0; e < 3; ++e) {
    ASSERT_TRUE(world->reset(ResetSpec::standing()));
    EXPECT_EQ(stand(*world), resets[static_cast<std::size_t>(e)]) << "reset " << e;
  }
  mujoco_set_always_compile(false);
}

}  // namespace
}  // namespace stride::sim
