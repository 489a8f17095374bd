// Tests of the MuJoCo engine: the generated model against the URDF (masses, inertias, axes,
// armature), errors, the igus robot standing on MuJoCo's soft contact as deep as on Simbody's
// contact law, and determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine_test_models.hpp"
#include "mujoco/mujoco_engine.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {
namespace {

EngineModel igus_model(const RobotModel& robot) {
  EngineModel m = engine_test::neutral_model(robot);
  m.left_foot = robot.link_index("left_foot_link");
  m.right_foot = robot.link_index("right_foot_link");
  return m;
}

TEST(MujocoEngine, TheModelHasTheUrdfsMassesInertiasAxesAndArmature) {
  RobotModel robot;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), robot));
  EngineModel model = igus_model(robot);
  for (std::size_t l = 0; l < robot.links().size(); ++l)
    model.link_mass_scale[l] = 1.0 + 0.01 * static_cast<double>(l);
  for (std::size_t j = 0; j < robot.joints().size(); ++j)
    model.joint_armature[j] = 0.001 * static_cast<double>(j + 1);
  model.ball.present = true;
  auto engine = make_mujoco_engine();
  const Status s = engine->build(model);
  ASSERT_TRUE(s) << s.message();
  const mjModel* m = mujoco_model_of(*engine);
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->nbody, static_cast<int>(robot.links().size()) + 2);  // world, links, ball
  EXPECT_EQ(m->njnt, static_cast<int>(robot.joints().size()) + 2);  // hinges, 2 free joints
  double total = 0.0, expected_total = 0.0;
  for (std::size_t l = 0; l < robot.links().size(); ++l) {
    const LinkSpec& link = robot.links()[l];
    const int b = mj_name2id(m, mjOBJ_BODY, ("l" + std::to_string(l)).c_str());
    ASSERT_GE(b, 0);
    const double scale = model.link_mass_scale[l];
    EXPECT_NEAR(m->body_mass[b], scale * link.mass, 1e-12) << link.name;
    total += m->body_mass[b];
    expected_total += scale * link.mass;
    // MuJoCo keeps the principal inertia and its frame: rebuild the full tensor.
    const Eigen::Quaterniond q(m->body_iquat[4 * b], m->body_iquat[4 * b + 1],
                               m->body_iquat[4 * b + 2], m->body_iquat[4 * b + 3]);
    const Eigen::Vector3d principal(m->body_inertia[3 * b], m->body_inertia[3 * b + 1],
                                    m->body_inertia[3 * b + 2]);
    const Eigen::Matrix3d inertia =
        q.toRotationMatrix() * principal.asDiagonal() * q.toRotationMatrix().transpose();
    EXPECT_LT((inertia - scale * link.inertia).norm(), 1e-8 * (1.0 + link.inertia.norm()))
        << link.name;
    const Eigen::Vector3d com(m->body_ipos[3 * b], m->body_ipos[3 * b + 1],
                              m->body_ipos[3 * b + 2]);
    EXPECT_LT((com - link.com).norm(), 1e-12) << link.name;
  }
  EXPECT_NEAR(total, expected_total, 1e-12);
  for (std::size_t j = 0; j < robot.joints().size(); ++j) {
    const JointSpec& joint = robot.joints()[j];
    const int id = mj_name2id(m, mjOBJ_JOINT, ("j" + std::to_string(j)).c_str());
    ASSERT_GE(id, 0);
    EXPECT_EQ(m->jnt_type[id], mjJNT_HINGE);
    EXPECT_EQ(m->jnt_limited[id], 0);  // the servo models apply the joint stops
    const Eigen::Vector3d axis(m->jnt_axis[3 * id], m->jnt_axis[3 * id + 1],
                               m->jnt_axis[3 * id + 2]);
    EXPECT_LT((axis - joint.axis).norm(), 1e-12) << joint.name;
    EXPECT_NEAR(m->dof_armature[m->jnt_dofadr[id]], model.joint_armature[j], 1e-15);
    EXPECT_EQ(m->dof_damping[m->jnt_dofadr[id]], 0.0);
    EXPECT_EQ(m->body_parentid[m->jnt_bodyid[id]],
              mj_name2id(m, mjOBJ_BODY, ("l" + std::to_string(joint.parent_link)).c_str()));
  }
  EXPECT_EQ(m->opt.integrator, mjINT_EULER);
  EXPECT_EQ(m->opt.timestep, model.step_s);
  EXPECT_EQ(m->opt.gravity[2], -model.gravity_mps2);
}

TEST(MujocoEngine, LinkPosesFollowTheUrdfJointFrames) {
  RobotModel robot;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), robot));
  auto engine = make_mujoco_engine();
  ASSERT_TRUE(engine->build(igus_model(robot)));
  EngineStart start;
  start.joint_angles.assign(robot.joints().size(), 0.0);
  for (std::size_t j = 0; j < robot.joints().size(); ++j)
    start.joint_angles[j] = 0.1 * std::sin(static_cast<double>(j));
  start.torso_position = Eigen::Vector3d(0.1, 0.2, 1.0);
  start.torso_orientation = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ());
  start.tilt_axis = Eigen::Vector3d(1, 1, 0).normalized();
  start.tilt_angle = 0.2;
  ASSERT_TRUE(engine->start(start));
  Eigen::Isometry3d torso = Eigen::Isometry3d::Identity();
  torso.translation() = start.torso_position;
  torso.linear() =
      (Eigen::AngleAxisd(0.2, start.tilt_axis) * start.torso_orientation).toRotationMatrix();
  std::vector<Eigen::Isometry3d> pose(robot.links().size(), torso);
  for (std::size_t j = 0; j < robot.joints().size(); ++j) {
    const JointSpec& joint = robot.joints()[j];
    pose[static_cast<std::size_t>(joint.child_link)] =
        pose[static_cast<std::size_t>(joint.parent_link)] * joint.origin *
        Eigen::AngleAxisd(start.joint_angles[j], joint.axis);
    EXPECT_NEAR(engine->joint_angle(j), start.joint_angles[j], 1e-15);
  }
  for (std::size_t l = 0; l < robot.links().size(); ++l)
    EXPECT_LT((engine->link_pose(l).matrix() - pose[l].matrix()).norm(), 1e-12)
        << robot.links()[l].name;
}

TEST(MujocoEngine, BadInputIsOneLineNamingIt) {
  RobotModel robot;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), robot));
  auto engine = make_mujoco_engine();
  EngineModel model = igus_model(robot);
  model.joint_armature.pop_back();
  Status s = engine->build(model);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("armatures"), std::string::npos) << s.message();
  model = igus_model(robot);
  model.link_mass_scale[3] = -1.0;  // a negative mass: MuJoCo's compiler refuses it
  s = engine->build(model);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("MJCF"), std::string::npos) << s.message();
  EXPECT_EQ(s.message().find('\n'), std::string::npos);
  EXPECT_FALSE(engine->start(EngineStart{}));  // no successful build
  ASSERT_TRUE(engine->build(igus_model(robot)));
  s = engine->start(EngineStart{});
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("joint angles"), std::string::npos) << s.message();
}

/// Mean height of a foot's four stud tips [m] (the grass top minus it is the foot's sink).
double stud_tip(const RobotModel& robot, int foot, const Eigen::Isometry3d& pose) {
  double sum = 0.0;
  const auto& spheres = robot.links()[static_cast<std::size_t>(foot)].spheres;
  for (const CollisionSphere& s : spheres) sum += (pose * s.center).z() - s.radius;
  return sum / static_cast<double>(spheres.size());
}

TEST(MujocoEngine, TheIgusRobotStandsAsDeepInTheGrassAsOnSimbody) {
  // Simbody: the robot standing 3 s on Stride's contact law, held by its servos, on the
  // seed's grass, the contact of igus_model below (the next test stands both on turf).
  std::unique_ptr<SimWorld> world;
  WorldOptions options;
  options.contact = ContactOptions::seed();
  ASSERT_TRUE(SimWorld::create(options, world));
  const std::vector<Eigen::Isometry3d> initial = world->link_poses();
  const std::vector<double> angles = world->joint_angles();
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    hal::ServoCommand c;
    c.position_rad = igus_stand_pose()[i];
    c.p_gain = 32;
    c.torque_enable = true;
    world->set_servo_command(i, c);
  }
  for (int k = 0; k < 300; ++k) ASSERT_TRUE(world->advance_period());
  const RobotModel& robot = world->model();
  const int left = robot.link_index("left_foot_link"), right = robot.link_index("right_foot_link");
  const GroundTruth g = world->ground_truth();
  const double simbody_left = stud_tip(robot, left, g.left_foot);
  const double simbody_right = stud_tip(robot, right, g.right_foot);

  // MuJoCo: the same start, the joints held by a stiff PD torque.
  auto engine = make_mujoco_engine();
  EngineModel model = igus_model(robot);
  model.joint_armature.assign(robot.joints().size(), 0.0024);  // 6e-8 kg m^2 x 200^2
  ASSERT_TRUE(engine->build(model));
  EngineStart start;
  start.joint_angles = angles;
  start.torso_position = initial[0].translation();
  start.torso_orientation = Eigen::Quaterniond(initial[0].linear());
  ASSERT_TRUE(engine->start(start));
  std::vector<double> torque(robot.joints().size(), 0.0);
  std::string reason;
  double lowest_com = 1e9;
  for (int k = 0; k < 2500; ++k) {  // 5 s
    for (std::size_t j = 0; j < torque.size(); ++j)
      torque[j] = 100.0 * (angles[j] - engine->joint_angle(j)) - 1.0 * engine->joint_speed(j);
    ASSERT_EQ(engine->step(torque, reason), WorldStatus::kRunning) << reason;
    if (k > 500) lowest_com = std::min(lowest_com, engine->robot_center_of_mass().z());
  }
  const double mujoco_left =
      stud_tip(robot, left, engine->link_pose(static_cast<std::size_t>(left)));
  const double mujoco_right =
      stud_tip(robot, right, engine->link_pose(static_cast<std::size_t>(right)));
  const double top = model.contact.grass_thickness_m;
  std::printf(
      "sink into the grass [mm]: Simbody left %.2f right %.2f, MuJoCo left %.2f right %.2f\n",
      1e3 * (top - simbody_left), 1e3 * (top - simbody_right), 1e3 * (top - mujoco_left),
      1e3 * (top - mujoco_right));
  EXPECT_NEAR(mujoco_left, simbody_left, 0.002);
  EXPECT_NEAR(mujoco_right, simbody_right, 0.002);
  EXPECT_GT(top - mujoco_left, 0.002);  // in the grass, not on it
  // Stable: upright, at rest, on its eight studs carrying its weight.
  EXPECT_GT(engine->link_pose(0).linear()(2, 2), 0.95);
  EXPECT_LT(engine->torso_velocity().norm(), 1e-3);
  EXPECT_GT(lowest_com, engine->robot_center_of_mass().z() - 0.005);
  const ContactReport c = engine->contacts();
  EXPECT_EQ(c.left.points_in_contact, 4);
  EXPECT_EQ(c.right.points_in_contact, 4);
  EXPECT_EQ(c.other_contacts, 0);
  const double weight = robot.total_mass() * model.gravity_mps2;
  EXPECT_NEAR(c.left.force.z() + c.right.force.z(), weight, 0.01 * weight);
  EXPECT_NEAR(c.left.force.z(), c.right.force.z(), 0.1 * weight);
  EXPECT_NEAR(engine->torso_acceleration().norm(), 0.0, 0.05);
}

TEST(MujocoEngine, SimWorldStandsOnMujocoAsDeepAsOnSimbodyWithItsServos) {
  // The same world (servos, randomisation, placement) on both engines, the Stand pose held.
  double sink[2][2] = {};
  for (EngineKind kind : {EngineKind::kSimbody, EngineKind::kMujoco}) {
    WorldOptions options;
    options.engine = kind;
    std::unique_ptr<SimWorld> world;
    const Status s = SimWorld::create(options, world);
    ASSERT_TRUE(s) << s.message();
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      hal::ServoCommand c;
      c.position_rad = igus_stand_pose()[i];
      c.p_gain = 32;
      c.torque_enable = true;
      world->set_servo_command(i, c);
    }
    for (int k = 0; k < 500; ++k) ASSERT_TRUE(world->advance_period()) << to_string(kind);
    const GroundTruth g = world->ground_truth();
    const RobotModel& robot = world->model();
    const double top = options.contact.grass_thickness_m;
    const auto e = static_cast<std::size_t>(kind);
    sink[e][0] = top - stud_tip(robot, robot.link_index("left_foot_link"), g.left_foot);
    sink[e][1] = top - stud_tip(robot, robot.link_index("right_foot_link"), g.right_foot);
    EXPECT_GT(g.torso.linear()(2, 2), 0.95) << to_string(kind);
    EXPECT_LT(g.torso_linear_velocity.norm(), 0.01) << to_string(kind);
    EXPECT_EQ(g.left_contact.points_in_contact, 4) << to_string(kind);
    EXPECT_EQ(g.right_contact.points_in_contact, 4) << to_string(kind);
    const double weight = robot.total_mass() * options.gravity_mps2;
    EXPECT_NEAR(g.left_contact.force.z() + g.right_contact.force.z(), weight, 0.05 * weight);
  }
  std::printf("SimWorld, 5 s standing, sink [mm]: Simbody %.2f / %.2f, MuJoCo %.2f / %.2f\n",
              1e3 * sink[0][0], 1e3 * sink[0][1], 1e3 * sink[1][0], 1e3 * sink[1][1]);
  EXPECT_NEAR(sink[1][0], sink[0][0], 0.002);
  EXPECT_NEAR(sink[1][1], sink[0][1], 0.002);
}

/// The igus robot dropped from 5 cm with its joints limp but one torque pulse, and a ball.
std::uint64_t drop_hash(const RobotModel& robot, double pulse) {
  auto engine = make_mujoco_engine();
  EngineModel model = igus_model(robot);
  model.ball.present = true;
  EXPECT_TRUE(engine->build(model));
  EngineStart start;
  start.joint_angles.assign(robot.joints().size(), 0.0);
  start.torso_position = Eigen::Vector3d(0, 0, 0.5);
  start.ball_position = Eigen::Vector3d(0.2, 0.0, 0.2);
  start.ball_velocity = Eigen::Vector3d(-1.0, 0.0, 0.0);
  EXPECT_TRUE(engine->start(start));
  std::vector<double> torque(robot.joints().size(), 0.0);
  std::string reason;
  for (int k = 0; k < 500; ++k) {
    torque[3] = k < 10 ? pulse : 0.0;
    for (std::size_t j = 0; j < torque.size(); ++j)
      if (j != 3) torque[j] = -2.0 * engine->joint_angle(j) - 0.05 * engine->joint_speed(j);
    EXPECT_EQ(engine->step(torque, reason), WorldStatus::kRunning) << reason;
  }
  return engine->hash(14695981039346656037ULL);
}

TEST(MujocoEngine, SameInputsGiveTheSameHashAndAnotherTorqueAnother) {
  RobotModel robot;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), robot));
  const std::uint64_t a = drop_hash(robot, 0.5);
  EXPECT_EQ(drop_hash(robot, 0.5), a);
  EXPECT_NE(drop_hash(robot, 0.5000001), a);
}

/// One dropping episode (as drop_hash) on an engine that may have run others before.
std::uint64_t drop_episode(PhysicsEngine& engine, const EngineModel& model, double pulse) {
  EXPECT_TRUE(engine.build(model));
  const std::size_t joints = model.robot->joints().size();
  EngineStart start;
  start.joint_angles.assign(joints, 0.0);
  start.torso_position = Eigen::Vector3d(0, 0, 0.5);
  start.ball_position = Eigen::Vector3d(0.2, 0.0, 0.2);
  start.ball_velocity = Eigen::Vector3d(-1.0, 0.0, 0.0);
  EXPECT_TRUE(engine.start(start));
  engine.set_torso_force(Eigen::Vector3d(3.0, 0.0, 0.0));  // start() of the next one clears it
  std::vector<double> torque(joints, 0.0);
  std::string reason;
  for (int k = 0; k < 300; ++k) {
    torque[3] = k < 10 ? pulse : 0.0;
    for (std::size_t j = 0; j < torque.size(); ++j)
      if (j != 3) torque[j] = -2.0 * engine.joint_angle(j) - 0.05 * engine.joint_speed(j);
    EXPECT_EQ(engine.step(torque, reason), WorldStatus::kRunning) << reason;
  }
  return engine.hash(14695981039346656037ULL);
}

TEST(MujocoEngine, ARebuildOfTheSameModelCompilesNothingAndGivesAFreshEnginesBits) {
  RobotModel robot;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), robot));
  EngineModel model = igus_model(robot);
  model.ball.present = true;
  EngineModel heavier = model;
  heavier.link_mass_scale[2] = 1.05;
  heavier.friction = 0.8;
  // Fresh engines: the reference bits of each model.
  const std::uint64_t fresh = drop_episode(*make_mujoco_engine(), model, 0.5);
  const std::uint64_t fresh_heavier = drop_episode(*make_mujoco_engine(), heavier, 0.5);
  EXPECT_NE(fresh, fresh_heavier);

  auto engine = make_mujoco_engine();
  const std::int64_t before = mujoco_compile_count();
  EXPECT_EQ(drop_episode(*engine, model, 0.5), fresh);
  EXPECT_EQ(mujoco_compile_count(), before + 1);
  EXPECT_EQ(drop_episode(*engine, model, 0.5), fresh);  // the kept model, its data reset
  EXPECT_EQ(drop_episode(*engine, model, 0.5), fresh);
  EXPECT_EQ(mujoco_compile_count(), before + 1);
  // Other masses and friction: written into the kept model (episode_values.hpp).
  EXPECT_EQ(drop_episode(*engine, heavier, 0.5), fresh_heavier);
  EXPECT_EQ(drop_episode(*engine, model, 0.5), fresh);
  EXPECT_EQ(mujoco_compile_count(), before + 1);
  // The contact stiffness is not in the MJCF text: a kept model takes the new one.
  EngineModel stiffer = model;
  stiffer.contact.grass_stiffness_n_m *= 2.0;
  const std::uint64_t fresh_stiffer = drop_episode(*make_mujoco_engine(), stiffer, 0.5);
  EXPECT_NE(fresh_stiffer, fresh);
  const std::int64_t kept = mujoco_compile_count();
  EXPECT_EQ(drop_episode(*engine, stiffer, 0.5), fresh_stiffer);
  EXPECT_EQ(drop_episode(*engine, model, 0.5), fresh);
  EXPECT_EQ(mujoco_compile_count(), kept);
  // The old path (a compile at every build) gives the same bits.
  mujoco_set_always_compile(true);
  EXPECT_EQ(drop_episode(*engine, model, 0.5), fresh);
  EXPECT_EQ(mujoco_compile_count(), kept + 1);
  mujoco_set_always_compile(false);
}

/// Hashes after each of `episodes` walking-free episodes (Stand pose held 1 s) of one world,
/// reset between them, and the compiles the world made.
std::vector<std::uint64_t> world_episodes(const WorldOptions& options, int episodes,
                                          std::int64_t& compiles) {
  const std::int64_t before = mujoco_compile_count();
  std::unique_ptr<SimWorld> world;
  const Status s = SimWorld::create(options, world);
  EXPECT_TRUE(s) << s.message();
  std::vector<std::uint64_t> hashes;
  for (int e = 0; e < episodes; ++e) {
    if (e > 0) {
      EXPECT_TRUE(world->reset(ResetSpec::standing()));
    }
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      hal::ServoCommand c;
      c.position_rad = igus_stand_pose()[i] + 0.1 * static_cast<double>(e % 2);
      c.p_gain = 32;
      c.torque_enable = true;
      world->set_servo_command(i, c);
    }
    for (int k = 0; k < 100; ++k) EXPECT_TRUE(world->advance_period());
    hashes.push_back(world->state_hash());
  }
  compiles = mujoco_compile_count() - before;
  return hashes;
}

TEST(MujocoEngine, ResetsOfOneWorldCompileOnceAndGiveTheOldPathsBits) {
  WorldOptions options;
  options.engine = EngineKind::kMujoco;
  options.seed = 5;
  std::int64_t compiles = 0;
  const std::vector<std::uint64_t> kept = world_episodes(options, 4, compiles);
  EXPECT_EQ(compiles, 1);           // without randomised masses and friction: once per world
  mujoco_set_always_compile(true);  // the old path: a compile at every reset, the same bits
  const std::vector<std::uint64_t> old_path = world_episodes(options, 4, compiles);
  mujoco_set_always_compile(false);
  EXPECT_EQ(compiles, 4);
  EXPECT_EQ(kept, old_path);
  // A fresh world's first episode is the same as any world's first.
  EXPECT_EQ(world_episodes(options, 1, compiles).front(), kept.front());

  // Randomised masses, friction, trunk centre of mass and ground: written into the compiled
  // model at every reset, still one compile per world and the old path's bits.
  options.randomise.mass_range = 0.05;
  options.randomise.friction_range = 0.2;
  options.randomise.com_range = 0.01;
  options.randomise.contact_range = 0.5;
  const std::vector<std::uint64_t> randomised = world_episodes(options, 3, compiles);
  EXPECT_EQ(compiles, 1);
  mujoco_set_always_compile(true);
  EXPECT_EQ(world_episodes(options, 3, compiles), randomised);
  mujoco_set_always_compile(false);
}

TEST(MujocoEngine, AnExplodingStateEndsTheStepWithAReason) {
  RobotModel robot;
  ASSERT_TRUE(RobotModel::load_file(RobotModel::igus_path(), robot));
  auto engine = make_mujoco_engine();
  ASSERT_TRUE(engine->build(igus_model(robot)));
  EngineStart start;
  start.joint_angles.assign(robot.joints().size(), 0.0);
  start.torso_position = Eigen::Vector3d(0, 0, 0.5);
  ASSERT_TRUE(engine->start(start));
  engine->set_joint_speed(2, 500.0);
  std::string reason;
  EXPECT_EQ(engine->step(std::vector<double>(robot.joints().size(), 0.0), reason),
            WorldStatus::kExploded);
  EXPECT_NE(reason.find("exploding"), std::string::npos) << reason;
  engine->set_joint_speed(2, std::nan(""));
  EXPECT_NE(engine->step(std::vector<double>(robot.joints().size(), 0.0), reason),
            WorldStatus::kRunning);
}

}  // namespace
}  // namespace stride::sim
