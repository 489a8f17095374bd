// SimWorld: the Simbody simulation of the igus robot on a grass field with a ball.
//
// Built from a URDF (RobotModel): a free-floating root link, one Pin mobilizer per revolute
// joint, the joint's servo model (ServoModel) on the servo-driven joints, rotor inertia
// J_rotor N^2 added about each driven joint axis, compliant contact of collision points (the
// foot studs, box corners, sphere bottoms) against a soft grass layer over solid ground, and a
// free ball. Integration is a fixed-step semi-explicit Euler scheme (u += h udot; q += h N u)
// that SimWorld runs itself, so one step costs exactly one Simbody realization to
// Stage::Acceleration.
//
// Driving it from outside (SimRobot, the virtual Dynamixel bus, evaluators):
//   set_servo_command(i, cmd)  -- registers in: goal, moving speed, P gain, torque limit/enable
//   advance_period()           -- one control period of physics, then the sensors are sampled
//   servo_state(i), imu()      -- registers out: present position/speed/load/temperature, IMU
// Every random draw (randomisation at reset, sensor noise) comes from the world's WorldRng.
// Simbody never appears in this header.
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

#include "stride/hal/command_frame.hpp"
#include "stride/hal/sensor_frame.hpp"
#include "stride/hal/status.hpp"
#include "stride/sim_hal/imu_model.hpp"
#include "stride/sim_hal/mx_servo.hpp"
#include "stride/sim_hal/robot_model.hpp"
#include "stride/sim_hal/servo_model.hpp"

namespace stride::sim {

/// URDF joint names of the 20 servos in Dynamixel-ID order (servo index = id - 1).
const std::array<std::string, hal::kServoCount>& igus_servo_joints();

/// The Stand pose of igus.md 3.4 in URDF joint angles (shoulder pitch = NUbots - pi/2), head 0.
const std::array<double, hal::kServoCount>& igus_stand_pose();

struct ContactOptions {
  double grass_thickness_m = 0.02;           ///< soft layer on top of the solid ground (seed: 2 cm)
  double grass_stiffness_n_m = 1500.0;       ///< per contact point [N/m]
  double grass_damping_n_s_m = 40.0;         ///< per contact point [N s/m]
  double ground_stiffness_n_m = 2.0e4;       ///< solid ground under the grass, per point [N/m]
  double ground_damping_n_s_m = 100.0;       ///< [N s/m]
  double friction = 1.0;                     ///< Coulomb coefficient (feet and links on the field)
  double tangential_stiffness_n_m = 5000.0;  ///< stick spring per point [N/m]
  double tangential_damping_n_s_m = 20.0;    ///< [N s/m]
  double ball_robot_stiffness_n_m = 5000.0;  ///< ball against robot links [N/m]
  double ball_robot_damping_n_s_m = 10.0;
};

struct BallOptions {
  bool present = true;
  double radius_m = 0.095;  ///< TeenSize ball (igus.md 5)
  double mass_kg = 0.26;
  double inertia_kg_m2 = 0.00156;   ///< thin-shell value of the seed's model
  double rolling_damping = 0.0016;  ///< angular velocity decay [N m s/rad]
};

struct ImuOptions {
  double accel_noise_std = 0.0;                          ///< white noise per sample [m/s^2]
  double gyro_noise_std = 0.0;                           ///< [rad/s]
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  ///< fixed bias [m/s^2]
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   ///< fixed bias [rad/s]
  double accel_bias_std = 0.0;  ///< per-reset random bias drawn on top [m/s^2]
  double gyro_bias_std = 0.0;   ///< [rad/s]
  /// The sensor chain (imu_model.hpp): ideal (true value at the period's end plus the white
  /// noise above) or the chips and CM730 of the robot (their own noise; the stds above unused).
  ImuChain chain = ImuChain::ideal();
  /// Typical values of the igus' CM730 IMU (used by `--noise on`).
  static ImuOptions noisy();
};

/// Which servo law drives the joints: the seed's (Gazebo figures, ServoModel) or the MX servo
/// identified on a bench (MxServo: firmware duty law, DC motor with back-EMF, BAM's M6
/// friction, backlash, the identified armature).
enum class ServoLaw { kSeed, kIdentified };

struct ServoOptions {
  ServoLaw law = ServoLaw::kSeed;
  // ServoLaw::kIdentified: the published MX parameters (mx_servo_params) with these options.
  MxFrictionModel friction_model = MxFrictionModel::kM6;
  double backlash_rad = 0.33 * 3.14159265358979323846 / 180.0;  ///< e-manual: 20 arcmin
  double driver_drop_v = 0.27;          ///< fitted to BAM's no-load speed table (mx_servo.hpp)
  double kp_per_register = 4.0 / 2.54;  ///< N m/rad per P unit (see README: the seed's 4 g)
  double viscous_friction = 1.0;        ///< seed 1 [N m s/rad]
  double coulomb_friction = 0.5;        ///< seed 0.5 [N m]
  /// Motor rotor inertia before the gearbox [kg m^2]; reflected as J N^2 (N = 200 or 225).
  double rotor_inertia_kg_m2 = 6.0e-8;
};

/// Seeded randomisation applied at every reset (relative ranges are uniform +-range).
struct Randomisation {
  double friction_range = 0.0;       ///< friction coefficient scale
  double mass_range = 0.0;           ///< per-link mass and inertia scale
  double strength_range = 0.0;       ///< per-servo stall torque scale
  double latency_probability = 0.0;  ///< chance of one control tick of command latency
};

struct WorldOptions {
  std::filesystem::path urdf = RobotModel::igus_path();
  /// The robot model already parsed (from `urdf`): set by callers that build many worlds of
  /// one model, such as the optimiser, to skip reading the file again; null reads `urdf`.
  std::shared_ptr<const RobotModel> model;
  std::array<std::string, hal::kServoCount> servo_joints = igus_servo_joints();
  /// Servo models in servo order (default: the shipped servo table's models).
  std::array<fw::ServoModel, hal::kServoCount> servo_models{};
  bool servo_models_from_table = true;
  std::int64_t physics_step_ns = 2'000'000;     ///< fixed integration step
  std::int64_t control_period_ns = 10'000'000;  ///< one advance_period(); multiple of the step
  double battery_voltage_v = 14.8;
  double gravity_mps2 = 9.81;
  ServoOptions servo;
  ContactOptions contact;
  BallOptions ball;
  ImuOptions imu;
  Randomisation randomise;
  std::uint64_t seed = 1;
  /// A state with a speed above this [rad/s or m/s] counts as exploded.
  double max_speed = 200.0;
};

/// Initial conditions for reset().
struct ResetSpec {
  std::array<double, hal::kServoCount> joint_angles{};  ///< servo joints [rad]
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

enum class WorldStatus : std::uint8_t {
  kRunning = 0,
  kNonFinite,          ///< NaN or infinity in the state
  kExploded,           ///< a speed above WorldOptions::max_speed
  kIntegratorFailure,  ///< Simbody threw during a step
};
const char* to_string(WorldStatus status);

struct FootContact {
  int points_in_contact = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< total contact force on the foot [N]
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

/// IMU reading in the torso frame.
struct ImuReading {
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  ///< specific force [m/s^2]
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   ///< angular rate [rad/s]
};

class SimWorld {
 public:
  /// Loads the URDF, builds the Simbody system and resets to ResetSpec::standing().
  static Status create(const WorldOptions& options, std::unique_ptr<SimWorld>& out);
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

  /// Advances one control period (several physics steps), then samples the sensors.
  /// Returns false (and does nothing) once the status is not kRunning.
  bool advance_period();
  /// Advances one physics step (tests and benchmarks).
  bool step();

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
