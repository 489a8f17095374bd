// PhysicsEngine: the one small interface a physics engine implements for SimWorld.
//
// SimWorld keeps everything that does not depend on the engine: the robot model, the servo
// models (they turn the engine's joint angles and speeds into joint torques every physics
// step), the IMU chain, the randomisation draws, command latency, episodes and ground truth.
// An engine owns the rigid bodies, the contact of robot and ball with the field (and with each
// other) and the integration of one fixed physics step.
//
// Model/data split, as in MuJoCo: EngineModel is what is fixed for one episode (SimWorld
// rebuilds the engine at every reset because the randomised masses change it; an engine may
// keep what an equal model built before, as MuJoCo keeps its compiled mjModel, as long as the
// results are those of a fresh build bit for bit); the engine's state changes per step. The
// sequence is build(), start(), then step() repeatedly, reading joint_angle()/joint_speed()
// before each step and the outputs after it; the state is defined only after start().
//
// Units: SI. World frame: x forward, y left, z up; the solid ground is at z = 0 and the top of
// the grass layer at z = ContactOptions::grass_thickness_m. Joint angle 0 is the URDF zero;
// the angle is about the joint's axis (RobotModel). Link poses are those of the URDF link
// frames (not the centres of mass).
//
// Real-time rules: build() and start() may allocate and throw nothing (errors come back as a
// Status); step() and every query allocate nothing and never throw.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/sim_hal/robot_model.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::sim {

/// What one episode's physics is built from (fixed until the next build()).
struct EngineModel {
  /// The robot (links parent-before-child, links[0] the free-floating root). Must outlive
  /// the engine's use of it.
  const RobotModel* robot = nullptr;
  /// Per link: its mass and inertia scale after randomisation (1 = the URDF's).
  std::vector<double> link_mass_scale;
  /// The root link's (the trunk's) centre of mass moved by randomisation, in its frame [m].
  Eigen::Vector3d root_com_shift = Eigen::Vector3d::Zero();
  /// Per joint: reflected rotor inertia (armature) about the joint axis [kg m^2].
  std::vector<double> joint_armature;
  /// Indices of the two feet in robot->links() (-1 if absent): their contacts are reported.
  int left_foot = -1, right_foot = -1;
  ContactOptions contact;
  double friction = 1.0;  ///< Coulomb coefficient of this episode (randomised)
  BallOptions ball;
  double gravity_mps2 = 9.81;
  double step_s = 0.002;  ///< fixed physics step [s]
  /// A generalised speed above this [rad/s or m/s] ends the episode as kExploded.
  double max_speed = 200.0;
};

/// Initial state for start(): everything at rest except the ball's velocity. The torso's
/// orientation is the rotation `tilt_angle` about the world axis `tilt_axis` applied after
/// `torso_orientation` (SimWorld levels the feet with the tilt); engines compose it in their
/// own arithmetic, so that a placement is the same bits as the engine's own kinematics.
struct EngineStart {
  std::vector<double> joint_angles;  ///< per model joint [rad]
  std::vector<double> joint_speeds;  ///< per model joint [rad/s]; empty: every joint at rest
  Eigen::Vector3d torso_position = Eigen::Vector3d::Zero();  ///< root link origin [m]
  Eigen::Quaterniond torso_orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d tilt_axis = Eigen::Vector3d::UnitZ();  ///< unit, world frame
  double tilt_angle = 0.0;                               ///< [rad]
  /// Velocity of the root link's origin and its angular velocity (world frame).
  Eigen::Vector3d torso_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d torso_angular_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d ball_position = Eigen::Vector3d::Zero();  ///< ball centre [m]
  Eigen::Vector3d ball_velocity = Eigen::Vector3d::Zero();  ///< [m/s]
};

/// Contacts with the field at the end of the last step.
struct ContactReport {
  FootContact left, right;
  int other_contacts = 0;  ///< contact points (or pairs) of non-foot links touching the field
};

class PhysicsEngine {
 public:
  virtual ~PhysicsEngine() = default;

  /// Builds bodies, joints and contacts for `model`. Errors name what could not be built.
  virtual Status build(const EngineModel& model) = 0;
  /// Places robot and ball at time 0 with the given speeds (zero: at rest).
  virtual Status start(const EngineStart& start) = 0;

  /// Angle [rad] and speed [rad/s] of model joint `joint` now.
  virtual double joint_angle(std::size_t joint) const = 0;
  virtual double joint_speed(std::size_t joint) const = 0;
  /// Advances one physics step with `joint_torque` (one per model joint [N m], held for the
  /// step) acting on the joints. Returns kRunning, or why the step failed with a one-line
  /// `reason` (the state is then not to be stepped again).
  virtual WorldStatus step(const std::vector<double>& joint_torque, std::string& reason) = 0;
  virtual double time_s() const = 0;

  /// URDF frame of link `link` in the world.
  virtual Eigen::Isometry3d link_pose(std::size_t link) const = 0;
  /// Linear velocity of the root link's origin and its angular velocity (world frame).
  virtual Eigen::Vector3d torso_velocity() const = 0;
  virtual Eigen::Vector3d torso_angular_velocity() const = 0;
  /// Acceleration of the root link's origin during the last step (world frame) [m/s^2].
  virtual Eigen::Vector3d torso_acceleration() const = 0;
  /// Centre of mass of the robot alone (not the ball) [m].
  virtual Eigen::Vector3d robot_center_of_mass() const = 0;
  virtual Eigen::Vector3d ball_position() const = 0;
  virtual Eigen::Vector3d ball_velocity() const = 0;
  virtual ContactReport contacts() const = 0;

  /// Folds the engine's complete state (time, positions, speeds, contact memory) into an
  /// FNV-1a 64 hash: two runs agree bit for bit exactly when their hashes do.
  virtual std::uint64_t hash(std::uint64_t seed) const = 0;
  /// Test hook: sets the speed of model joint `joint` (to provoke an exploding state).
  virtual void set_joint_speed(std::size_t joint, double speed) = 0;
  /// An external force [N] (world frame) on the root link at its centre of mass, acting on
  /// every following step until it is set again (zero: none). start() clears it.
  virtual void set_torso_force(const Eigen::Vector3d& force) = 0;
};

/// The engine of the given kind, not yet built.
std::unique_ptr<PhysicsEngine> make_physics_engine(EngineKind kind);

/// FNV-1a 64 over raw bytes (the hash every engine and SimWorld fold their state into).
std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t bytes);

/// The check every engine applies after a step: finite positions and speeds, no speed above
/// `max_speed`. Returns kRunning or the failure with a one-line reason naming the element.
WorldStatus check_state(const double* q, std::size_t nq, const double* u, std::size_t nu,
                        double max_speed, double time_s, std::string& reason);

}  // namespace stride::sim
