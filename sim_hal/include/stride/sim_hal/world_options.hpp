// The options of a simulated world (what is fixed for a SimWorld's life), its status, and
// the physics engine that runs it. Plain data: no engine header appears here.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/firmware/servo_table.hpp"
#include "stride/hal/command_frame.hpp"
#include "stride/sim_hal/imu_model.hpp"
#include "stride/sim_hal/mx_servo.hpp"
#include "stride/sim_hal/robot_model.hpp"

namespace stride::sim {

/// URDF joint names of the 20 servos in Dynamixel-ID order (servo index = id - 1).
const std::array<std::string, hal::kServoCount>& igus_servo_joints();

/// The physics engine behind a SimWorld (physics_engine.hpp). Simbody runs Stride's own
/// compliant contact law; MuJoCo its own soft-contact solver, so that the two are independent.
enum class EngineKind : std::uint8_t { kSimbody, kMujoco };
const char* to_string(EngineKind kind);
/// "simbody" or "mujoco"; false for anything else.
bool parse_engine_kind(std::string_view text, EngineKind& out);

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
  /// MuJoCo only: model the solid ground under the grass (a second plane at z = 0, its own
  /// stiffness per contact). Simbody always has it; MuJoCo's seed world leaves it out (the
  /// grass spring continues below 2 cm), so that its earlier figures stand.
  bool mujoco_solid_ground = false;

  /// The seed's Gazebo grass (the defaults above): a 2 cm soft layer.
  static ContactOptions seed() { return {}; }
  /// Artificial turf (issue 29, sim_hal/models/README.md "Turf"): the seed's grass spring in a
  /// 5 mm layer over the solid ground, modelled on both engines, and a stick spring softer than
  /// the normal spring as in an elastic contact (Mindlin: k_t / k_n = 2(1-nu)/(2-nu), 0.7 for
  /// rubber infill, nu 0.45; the seed's 5000 N/m is 3.3 times the normal 1500 N/m). A standing
  /// robot sinks at most about 5 mm and a foot in single support 5.5 mm (seed: 5 and 11 mm):
  /// turf deforms 4-11 mm under an athlete's impact (FIFA), far less under a 6.5 kg robot.
  static ContactOptions turf() {
    ContactOptions c;
    c.grass_thickness_m = 0.005;
    c.tangential_stiffness_n_m = 1000.0;
    c.mujoco_solid_ground = true;
    return c;
  }
  /// A carpet or stiff floor (issue 41 point 1, sim_hal/models/README.md "Grounds"): a 3 mm
  /// pile as stiff as the solid ground under it (the seed's solid ground, 2e4 N/m and
  /// 100 N s/m per point: the stiffest contact this explicit 2 ms step is known to run; teams'
  /// MuJoCo models use a rigid plane), the stick spring 0.7 of the normal one (Mindlin, as on
  /// turf). A standing robot's studs sink 0.4 mm (7.9 N per stud) on both engines; a walking
  /// stance foot's 0.4 mm at the median tick, 1.2-1.4 mm at a landing (models/README.md).
  static ContactOptions hard() {
    ContactOptions c = turf();
    c.grass_thickness_m = 0.003;
    c.grass_stiffness_n_m = 2.0e4;
    c.grass_damping_n_s_m = 100.0;
    c.tangential_stiffness_n_m = 0.7 * 2.0e4;
    return c;
  }
  /// A deep artificial turf (issue 41 point 1): a 15 mm layer (long pile, infill and shock
  /// pad) at 2000 N/m per point, so that a standing robot's studs sink 4.0 mm (measured on both
  /// engines) and a walking stance foot (up to 8 mm) never reaches the base, critically damped for
  /// one stud's share of the standing robot (2 sqrt(k m / 8) = 80 N s/m, twice turf's 40: FIFA's
  /// 55-70 % shock absorption is a layer that dissipates most of an impact); stick spring 0.7 of
  /// the normal.
  static ContactOptions soft() {
    ContactOptions c = turf();
    c.grass_thickness_m = 0.015;
    c.grass_stiffness_n_m = 2000.0;
    c.grass_damping_n_s_m = 80.0;
    c.tangential_stiffness_n_m = 0.7 * 2000.0;
    return c;
  }
};

/// "seed", "turf", "soft" or "hard" (ContactOptions::seed(), ::turf(), ::soft(), ::hard());
/// false for anything else.
bool parse_contact_kind(std::string_view text, ContactOptions& out);
/// The name parse_contact_kind gives `contact`'s ground (every figure but the friction equal to
/// that ground's), or "custom".
const char* contact_kind_name(const ContactOptions& contact);

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
  ImuChain chain{};
  /// Typical noise of the igus' CM730 IMU on (`--noise on`) or every noise off: the white noise
  /// and biases above, and the chain's own chip noise. The chain itself is kept.
  void set_noise(bool on);
};

/// The IMU model by name (`--imu`): ideal, the stock CM730's chain (cm730) or the CM730 with
/// NimbRo's firmware (cm730-nimbro: 16-bit registers and a magnetometer, imu_model.hpp).
enum class ImuKind : std::uint8_t { kIdeal, kCm730, kCm730Nimbro };
/// "ideal", "cm730" or "cm730-nimbro".
const char* to_string(ImuKind kind);

/// Which servo law drives the joints: the seed's (Gazebo figures, ServoModel) or the MX servo
/// identified on a bench (MxServo: firmware duty law, DC motor with back-EMF, BAM's M6
/// friction, backlash, the identified armature).
enum class ServoLaw { kSeed, kIdentified };

struct ServoOptions {
  ServoLaw law = ServoLaw::kIdentified;
  // ServoLaw::kIdentified: the published MX parameters (mx_servo_params) with these options.
  MxFrictionModel friction_model = MxFrictionModel::kM6;
  double backlash_rad = fw::kMxBacklashRad;  ///< e-manual: 20 arcmin (MX motor table)
  double driver_drop_v = 0.27;               ///< fitted to BAM's no-load speed table (mx_servo.hpp)
  double kp_per_register = 4.0 / 2.54;       ///< N m/rad per P unit (see README: the seed's 4 g)
  double viscous_friction = 1.0;             ///< seed 1 [N m s/rad]
  double coulomb_friction = 0.5;             ///< seed 0.5 [N m]
  /// Motor rotor inertia before the gearbox [kg m^2]; reflected as J N^2 (N = 200 or 225).
  double rotor_inertia_kg_m2 = 6.0e-8;
};

/// The largest centre-of-mass randomisation, Randomisation::com_range [m].
inline constexpr double kMaxComRange = 0.05;

/// Seeded randomisation applied at every reset (relative ranges are uniform +-range).
struct Randomisation {
  double friction_range = 0.0;       ///< friction coefficient scale
  double mass_range = 0.0;           ///< per-link mass and inertia scale
  double strength_range = 0.0;       ///< per-servo stall torque scale
  double latency_probability = 0.0;  ///< chance of one control tick of command latency
  /// The ground drawn at each reset (grounds.hpp draw_ground): u uniform in [-range, range),
  /// the contact's figures moved the fraction |u| of the way (on a log scale) from the world's
  /// ground towards the hard ground (u < 0) or the soft one (u > 0). 0: no draw at all.
  double contact_range = 0.0;
  /// The trunk's centre of mass moved at each reset, x and y each uniform in +-range [m]
  /// (sim_hal/models/make_variants.py's variants move it 1 cm): robots that differ from the
  /// URDF as real ones do. 0: no draw at all.
  double com_range = 0.0;
  /// The robot as it may be (issue 54 point 2): every servo's friction scale, every servo's
  /// motor torque scale and the supply voltage, each drawn once per reset, uniform in
  /// [min, max], on top of the world's (RobotCalibration, battery_voltage_v). Equal bounds draw
  /// nothing: the scales are then that value (1: the world's), a supply of 0 the world's.
  double servo_friction_min = 1.0, servo_friction_max = 1.0;
  double servo_torque_min = 1.0, servo_torque_max = 1.0;
  double supply_min_v = 0.0, supply_max_v = 0.0;  ///< [V]; 0, 0: the world's supply
};

/// The servo and supply draws' bounds: each pair ordered, the scales in 0.1..3, the supply
/// 0, 0 (the world's) or in 6..20 V; the error names the pair and both values.
Status check_servo_draws(const Randomisation& r);

/// How one robot differs from the model (issue 30 point 3): what `stride calibrate` fits from
/// the robot's flight logs and a world file holds (world_file.hpp). The nominal values change
/// nothing. The supply voltage and the IMU's fixed biases are WorldOptions::battery_voltage_v
/// and ImuOptions::gyro_bias / accel_bias.
struct RobotCalibration {
  static constexpr int kMaxLatencyTicks = 3;
  /// Scale of every MX-64's / MX-106's motor torque (on top of the per-reset randomisation):
  /// wear, a weaker batch, a servo model that is not the datasheet's.
  double torque_scale_mx64 = 1.0;
  double torque_scale_mx106 = 1.0;
  /// Scale of every servo's friction (every term of the servo law in use).
  double friction_scale = 1.0;
  /// Control periods between a command and the servos acting on it (bus latency, 0..3), on top
  /// of Randomisation::latency_probability's one tick.
  int latency_ticks = 0;
  /// The trunk link's mass and inertia scale (battery, cables, a heavier head).
  double trunk_mass_scale = 1.0;
  /// The trunk's centre of mass moved in the trunk frame [m] (x forward, y left).
  Eigen::Vector2d trunk_com_offset_m = Eigen::Vector2d::Zero();

  double torque_scale(fw::ServoModel model) const {
    return model == fw::ServoModel::kMx106 ? torque_scale_mx106 : torque_scale_mx64;
  }
};

/// A push on the trunk (issue 29 point 4, `stride sim walk --push T,DIR,IMPULSE`): the impulse
/// `impulse_n_s` along the horizontal direction `direction_rad`, measured anticlockwise from the
/// robot's heading (the torso's yaw when the push starts: 0 forward, pi/2 left), starting
/// `time_s` after the episode start. It is applied as a constant horizontal force of
/// impulse / kPushDuration at the trunk's centre of mass over the physics steps of
/// kPushDuration (rounded to whole steps, the force scaled so that the impulse is exact), so
/// that each engine passes it through its own multibody dynamics and contact, as a hand or a
/// pendulum striking the chest would.
struct TorsoPush {
  static constexpr double kPushDuration = 0.01;  ///< [s], one control period at 100 Hz
  double time_s = 0.0;
  double direction_rad = 0.0;
  double impulse_n_s = 0.0;
};

/// A named world (issue 29 point 6): the robot's servo law, IMU chain and field contact.
/// kFaithful is the default everywhere: the identified MX servo law, the CM730 IMU chain and
/// turf. kSeed is the thesis's world, kept by name to reproduce it: the seed's servo law (its
/// Gazebo figures), an ideal IMU and its 2 cm grass. The firmware's walk defaults belong to the
/// faithful world; the thesis's are firmware/config/seed-walk.json.
enum class WorldPreset : std::uint8_t { kFaithful, kSeed };
const char* to_string(WorldPreset preset);
/// "faithful" or "seed"; false for anything else.
bool parse_world_preset(std::string_view text, WorldPreset& out);

/// The default world's physics step [us] and random seed (WorldSpec's defaults, which
/// WorldOptions' member initialisers share).
inline constexpr std::int64_t kDefaultPhysicsStepUs = 2000;
inline constexpr std::uint64_t kDefaultWorldSeed = 1;
/// The igus robot's nominal supply voltage [V] (WorldOptions' and a world file's default).
inline constexpr double kNominalSupplyVoltage = fw::kMxNominalSupplyV;

/// The models of a world: the member initialisers are the faithful world (WorldPreset
/// kFaithful; kSeed is the thesis's world) with the sensor noise off, the quiet world the tests
/// and benches build on. A command's default world is WorldSpec{}.to_options() (world_spec.hpp:
/// the same world with the noise on, as `--noise` defaults); ask for it there rather than
/// repeating its options here.
struct WorldOptions {
  EngineKind engine = EngineKind::kSimbody;
  std::filesystem::path urdf = RobotModel::igus_path();
  /// The robot model already parsed (from `urdf`): set by callers that build many worlds of
  /// one model, such as the optimiser, to skip reading the file again; null reads `urdf`.
  std::shared_ptr<const RobotModel> model;
  std::array<std::string, hal::kServoCount> servo_joints = igus_servo_joints();
  /// Servo models in servo order (default: the shipped servo table's models).
  std::array<fw::ServoModel, hal::kServoCount> servo_models{};
  bool servo_models_from_table = true;
  std::int64_t physics_step_ns = kDefaultPhysicsStepUs * 1000;  ///< fixed integration step
  std::int64_t control_period_ns = 10'000'000;  ///< one advance_period(); multiple of the step
  double battery_voltage_v = kNominalSupplyVoltage;
  double gravity_mps2 = 9.81;
  ServoOptions servo;
  ContactOptions contact = ContactOptions::turf();
  BallOptions ball;
  ImuOptions imu;
  Randomisation randomise;
  RobotCalibration robot;
  std::uint64_t seed = kDefaultWorldSeed;
  /// A state with a speed above this [rad/s or m/s] counts as exploded.
  double max_speed = 200.0;
  /// Pushes on the trunk during each episode (times from the episode's reset).
  std::vector<TorsoPush> pushes;

  /// Sets the servo law, the IMU chain (keeping its noise switch) and the contact of `preset`.
  void apply(WorldPreset preset);
  /// The IMU chain: the CM730's (true) or the ideal sensor, keeping the chain's noise switch.
  void use_cm730_imu(bool cm730);
  /// The IMU chain of `kind`, keeping the chain's noise switch.
  void use_imu(ImuKind kind);
  /// Which of the named chains `imu.chain` is (kCm730 for a chain with no magnetometer).
  ImuKind imu_kind() const;
  /// The thesis's world (WorldPreset::kSeed) with every other option at its default.
  static WorldOptions seed_world() {
    WorldOptions o;
    o.apply(WorldPreset::kSeed);
    return o;
  }
};

enum class WorldStatus : std::uint8_t {
  kRunning = 0,
  kNonFinite,          ///< NaN or infinity in the state
  kExploded,           ///< a speed above WorldOptions::max_speed
  kIntegratorFailure,  ///< the engine failed during a step
};
const char* to_string(WorldStatus status);

struct FootContact {
  int points_in_contact = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< total contact force on the foot [N]
};

}  // namespace stride::sim
