// SimWorld: the simulated igus robot on a grass field with a ball, on a physics engine.
//
// Built from a URDF (RobotModel). What does not depend on the engine lives here: the servo
// models (SimServo, sim_servo.hpp: the seed's law or the identified MX servo) turn each joint's
// angle and speed into a torque every physics step; the IMU (ImuSampler) reads the torso's
// motion; the seeded randomisation (friction, masses, servo strength, command latency, IMU
// bias) is drawn at every reset; the robot is placed by forward kinematics. The engine
// (physics_engine.hpp, chosen by WorldOptions::engine) owns bodies, contact and the step:
// Simbody with Stride's compliant grass contact, or MuJoCo with its own soft contact.
//
// Driving it from outside (SimRobot, the virtual Dynamixel bus, evaluators):
//   set_servo_command(i, cmd)  -- registers in: goal, moving speed, P gain, torque limit/enable
//   advance_period()           -- one control period of physics, then the sensors are sampled
//   servo_state(i), imu()      -- registers out: present position/speed/load/temperature, IMU
// Every random draw (randomisation at reset, sensor noise) comes from the world's WorldRng.
// No engine header appears here.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/hal/command_frame.hpp"
#include "stride/hal/sensor_frame.hpp"
#include "stride/sim_hal/imu_model.hpp"
#include "stride/sim_hal/imu_sampler.hpp"
#include "stride/sim_hal/mx_servo.hpp"
#include "stride/sim_hal/robot_model.hpp"
#include "stride/sim_hal/servo_model.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::sim {

/// The Stand pose of igus.md 3.4 in URDF joint angles (shoulder pitch = NUbots - pi/2), head 0.
const std::array<double, hal::kServoCount>& igus_stand_pose();

/// Initial conditions for reset().
struct ResetSpec {
  std::array<double, hal::kServoCount> joint_angles{};  ///< servo joints [rad]
  /// Servo joint speeds [rad/s] (the other joints, the torso and the ball start at rest).
  std::array<double, hal::kServoCount> joint_speeds{};
  /// With joint speeds: give the trunk the velocity that keeps the lower foot still, as a foot
  /// standing on the ground is (false: the trunk starts at rest).
  bool still_lower_foot = false;
  /// The commands written before the start, the latest first (a replay gives the logged ones):
  /// with command latency (RobotCalibration::latency_ticks) the servos act on them first.
  /// Empty: a hold of joint_angles at P 32.
  std::vector<hal::CommandFrame> previous_commands;
  /// With a NaN z: sink the robot into the grass until the contacts' static springs carry its
  /// weight, as a robot that has been standing is (false: the lowest point on the grass top).
  bool sink_into_grass = false;
  /// Torso (root link) position; a NaN z means "lowest contact point resting on the grass".
  Eigen::Vector3d torso_position{0.0, 0.0, std::numeric_limits<double>::quiet_NaN()};
  Eigen::Quaterniond torso_orientation = Eigen::Quaterniond::Identity();
  /// Tilt the torso (after torso_orientation) so that the mean sole normal points straight up:
  /// the Stand pose carries a forward body tilt, so this is how the robot stands on both feet.
  bool level_feet = true;
  Eigen::Vector3d ball_position{0.3, 0.0,
                                std::numeric_limits<double>::quiet_NaN()};  ///< NaN z: on the grass
  Eigen::Vector3d ball_velocity = Eigen::Vector3d::Zero();
  /// The robot standing in the Stand pose of igus.md 3.4.
  static ResetSpec standing();
};

/// Ground truth for evaluators (world frame: x forward, y left, z up; the field at z = 0 is the
/// solid ground, the grass top at z = grass_thickness).
struct GroundTruth {
  double time_s = 0.0;
  Eigen::Isometry3d torso = Eigen::Isometry3d::Identity();
  Eigen::Vector3d torso_linear_velocity = Eigen::Vector3d::Zero();   ///< of the link origin
  Eigen::Vector3d torso_angular_velocity = Eigen::Vector3d::Zero();  ///< world frame
  /// Acceleration of the torso origin at the last physics step (world frame) [m/s^2].
  Eigen::Vector3d torso_linear_acceleration = Eigen::Vector3d::Zero();
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();
  Eigen::Isometry3d left_foot = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d right_foot = Eigen::Isometry3d::Identity();
  FootContact left_contact, right_contact;
  int other_contacts = 0;  ///< contact points of non-foot links touching the field
  Eigen::Vector3d ball_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d ball_velocity = Eigen::Vector3d::Zero();
};

class SimWorld {
 public:
  /// Loads the URDF, builds the engine and resets to ResetSpec::standing().
  static Status create(const WorldOptions& options, std::unique_ptr<SimWorld>& out);
  /// create(options) followed by reset(spec), bit for bit, without building and placing the
  /// robot for the start-up reset first (its random draws are still made, so the stream is
  /// the same).
  static Status create(const WorldOptions& options, const ResetSpec& spec,
                       std::unique_ptr<SimWorld>& out);
  /// This world made again as create(options, spec) would make it, bit for bit, keeping what it
  /// can: the engine object of the same kind keeps its built model and rebuilds only what the
  /// episode changes (the MuJoCo engine's compiled model; see physics_engine.hpp). For one
  /// world per worker thread, reused for episode after episode. After an error the world is
  /// not to be used again (make a new one).
  Status restart(const WorldOptions& options, const ResetSpec& spec);
  ~SimWorld();
  SimWorld(const SimWorld&) = delete;
  SimWorld& operator=(const SimWorld&) = delete;

  /// Restarts the episode: draws the randomisation, places robot and ball, clears the status.
  Status reset(const ResetSpec& spec);
  /// Restarts the world's random generator (the next reset draws from the new stream).
  void reseed(std::uint64_t seed);

  /// Registers of servo `index` (0..19); they act from the next advance_period().
  void set_servo_command(std::size_t index, const hal::ServoCommand& command);
  /// Forces torque off on every servo (emergency stop) while false.
  void set_torque_enable(bool enabled);
  /// Servo registers out: present position (quantised), speed, load, voltage, temperature,
  /// and an echo of the written registers.
  hal::ServoState servo_state(std::size_t index) const;
  /// The IMU sample taken at the end of the last period (noise and bias included).
  const ImuReading& imu() const;
  /// The IMU's fixed biases this episode: the options' plus the per-reset draw (noise on), in
  /// the torso frame (the truth a calibration of the IMU biases should find).
  const Eigen::Vector3d& episode_accel_bias() const;
  const Eigen::Vector3d& episode_gyro_bias() const;

  /// Advances one control period (several physics steps), then samples the sensors.
  /// Returns false (and does nothing) once the status is not kRunning.
  bool advance_period();
  /// Advances one physics step (tests and benchmarks).
  bool step();

  /// Peaks over the physics steps of the last advance_period() (impact measurements): the
  /// torso's acceleration magnitude [m/s^2], the largest |motor torque| of any servo
  /// (SimServo::motor_torque_nm) with that servo's index, and the largest |torque| on a servo's
  /// joint (motor, gearbox friction and end stop) [N m]. They read the state, change nothing.
  struct PeriodPeaks {
    double torso_accel_mps2 = 0.0;
    double servo_torque_nm = 0.0;
    int servo_index = -1;
    double joint_torque_nm = 0.0;
  };
  const PeriodPeaks& last_period_peaks() const;

  WorldStatus status() const;
  /// One line describing why the episode ended (empty while running).
  const std::string& failure_reason() const;

  GroundTruth ground_truth() const;
  /// The torso pose alone (cheaper than ground_truth()).
  Eigen::Isometry3d torso_pose() const;
  /// FNV-1a 64 over the bytes of time, q, u, servo set-points and contact anchors.
  std::uint64_t state_hash() const;

  double time_s() const;
  std::int64_t period_count() const;
  const WorldOptions& options() const;
  /// The ground of this episode: options().contact, or the one drawn at the last reset when
  /// options().randomise.contact_range > 0 (grounds.hpp).
  const ContactOptions& ground() const;
  /// How far the trunk's centre of mass was moved at the last reset, in the trunk's frame [m]
  /// (zero unless options().randomise.com_range > 0).
  Eigen::Vector3d trunk_com_shift() const;
  const RobotModel& model() const;
  double battery_voltage() const;
  /// Pose of every link of model() in the world frame (for drawings and recordings).
  std::vector<Eigen::Isometry3d> link_poses() const;
  /// Present angles of the model's joints (all of them, in model().joints() order).
  std::vector<double> joint_angles() const;
  /// True (unquantised) angle of servo `index`'s joint [rad].
  double servo_joint_angle(std::size_t index) const;
  /// Test hook: sets the speed of a model joint (to provoke an exploding state).
  void set_joint_speed(std::size_t joint, double speed);

  struct Impl;

 private:
  explicit SimWorld(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace stride::sim
