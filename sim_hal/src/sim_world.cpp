// SimWorld: servo and IMU models, randomisation and placement around a physics engine.
#include "stride/sim_hal/sim_world.hpp"

#include <algorithm>
#include <cmath>

#include "robot_placement.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/sim_hal/collision_points.hpp"
#include "stride/sim_hal/grounds.hpp"
#include "stride/sim_hal/physics_engine.hpp"
#include "stride/sim_hal/sim_servo.hpp"
#include "stride/sim_hal/world_rng.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::sim {

struct SimWorld::Impl {
  WorldOptions options;
  RobotModel model;
  WorldRng rng;
  std::unique_ptr<PhysicsEngine> engine;
  EngineModel engine_model;
  std::vector<CollisionPoint> collision;  ///< for placing the robot on the grass

  // Per model joint.
  std::vector<int> joint_servo;  ///< servo index or -1
  std::vector<double> joint_tau;
  // Per servo.
  std::array<int, hal::kServoCount> servo_joint{};
  std::array<std::unique_ptr<SimServo>, hal::kServoCount> servos;  ///< the world's servo law
  std::array<fw::ServoModel, hal::kServoCount> servo_models{};
  std::array<hal::ServoCommand, hal::kServoCount> written{};
  /// The commands written 1, 2, ... periods ago (latency: RobotCalibration, Randomisation).
  std::array<std::array<hal::ServoCommand, hal::kServoCount>,
             RobotCalibration::kMaxLatencyTicks + 1>
      delayed{};
  bool torque_enable = true;
  int left_foot = -1, right_foot = -1;

  // Randomised per reset.
  std::array<double, hal::kServoCount> strength{};
  int latency_ticks = 0;  ///< RobotCalibration's and the randomised tick
  /// The robot as it may be (Randomisation's servo and supply draws): scales on top of
  /// RobotCalibration's, and the supply voltage this reset [V].
  double friction_scale = 1.0, torque_scale = 1.0, supply_v = 0.0;
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero(), gyro_bias = Eigen::Vector3d::Zero();

  // Time and status.
  double h = 0.002;
  int steps_per_period = 5;
  std::int64_t periods = 0;
  WorldStatus status = WorldStatus::kRunning;
  std::string reason;
  ImuSampler imu;

  // Pushes (WorldOptions::pushes): physics steps since the reset, each push's first step,
  // the steps it lasts, and the torso's heading when it began.
  std::int64_t steps = 0;
  std::vector<std::int64_t> push_first_step;
  std::vector<double> push_heading;
  std::int64_t push_steps = 1;

  EngineKind engine_kind = EngineKind::kSimbody;
  SimWorld::PeriodPeaks peaks;  ///< of the last advance_period()

  Status configure();
  /// The randomisation of one reset, drawn from rng (a fixed number of draws whatever the
  /// ranges, and one more for the ground when its range is set), into engine_model and the
  /// per-reset fields.
  void draw_randomisation();
  /// The random draws of a reset followed by its first IMU sample, made and discarded: what
  /// create()'s start-up reset takes from the stream when a restart skips it.
  void skip_reset_draws();
  void apply_pushes();
  void servo_torques();
  bool step_once();
  TorsoMotion torso_motion() const {
    const Eigen::Isometry3d pose = engine->link_pose(0);
    return {pose.linear(), engine->torso_angular_velocity(), engine->torso_acceleration(),
            pose.translation()};
  }
};

Status check_servo_draws(const Randomisation& r) {
  const auto bounds = [](const char* name, double lo, double hi, double min, double max,
                         const char* unit) -> Status {
    if (!(lo >= min && hi <= max && lo <= hi))
      return Status::error(std::string(name) + "_min and _max: need " + fw::format_number(min) +
                           " <= min <= max <= " + fw::format_number(max) + unit + ", got " +
                           fw::format_number(lo) + " and " + fw::format_number(hi));
    return {};
  };
  if (Status s = bounds("servo_friction", r.servo_friction_min, r.servo_friction_max, 0.1, 3.0, "");
      !s)
    return s;
  if (Status s = bounds("servo_torque", r.servo_torque_min, r.servo_torque_max, 0.1, 3.0, ""); !s)
    return s;
  if (r.supply_min_v == 0.0 && r.supply_max_v == 0.0) return {};  // the world's supply
  return bounds("supply", r.supply_min_v, r.supply_max_v, 6.0, 20.0, " V");
}

namespace {

/// A scale drawn uniform in [lo, hi]; equal bounds draw nothing (the stream stays as it was).
double draw_between(double lo, double hi, WorldRng& rng) {
  return hi > lo ? rng.uniform(lo, hi) : lo;
}

}  // namespace

Status SimWorld::Impl::configure() {
  const WorldOptions& o = options;
  if (Status s = check_physics_step(o.physics_step_ns, o.control_period_ns); !s) return s;
  if (!(o.battery_voltage_v > 0.0) || !(o.max_speed > 0.0))
    return Status::error("battery voltage and max speed must be positive");
  if (Status s = check_calibration(calibration_of(o)); !s) return s;
  if (!(o.contact.grass_thickness_m >= 0.0) || !(o.contact.grass_stiffness_n_m > 0.0) ||
      !(o.contact.ground_stiffness_n_m > 0.0) || !(o.contact.friction >= 0.0) ||
      !(o.contact.tangential_stiffness_n_m > 0.0) || !(o.contact.grass_damping_n_s_m >= 0.0) ||
      !(o.contact.ground_damping_n_s_m >= 0.0) || !(o.contact.tangential_damping_n_s_m >= 0.0))
    return Status::error("contact: thickness, damping and friction must be >= 0, stiffness > 0");
  if (!(o.randomise.contact_range >= 0.0 && o.randomise.contact_range <= kMaxContactRange))
    return Status::error("contact_range: must be in 0..1");
  if (!(o.randomise.com_range >= 0.0 && o.randomise.com_range <= kMaxComRange))
    return Status::error("com_range: must be in 0.." + fw::format_number(kMaxComRange) + " m");
  if (Status s = check_servo_draws(o.randomise); !s) return s;
  supply_v = o.battery_voltage_v;
  for (const TorsoPush& p : o.pushes)
    if (!(p.time_s >= 0.0) || !std::isfinite(p.time_s) || !std::isfinite(p.direction_rad) ||
        !(p.impulse_n_s >= 0.0) || !std::isfinite(p.impulse_n_s))
      return Status::error("push: time and impulse must be finite and >= 0, direction finite");
  // The engine object stays across restarts on the same engine: it keeps what it built (the
  // compiled MuJoCo model, the Simbody system) and rebuilds only what an episode changes.
  if (!engine || engine_kind != o.engine) engine = make_physics_engine(o.engine);
  engine_kind = o.engine;
  if (!engine)
    return Status::error(std::string("engine '") + to_string(o.engine) +
                         "' is not available in this build");
  h = static_cast<double>(o.physics_step_ns) * 1e-9;
  steps_per_period = static_cast<int>(o.control_period_ns / o.physics_step_ns);
  push_steps = std::max<std::int64_t>(1, std::llround(TorsoPush::kPushDuration / h));
  push_first_step.clear();
  for (const TorsoPush& p : o.pushes)
    push_first_step.push_back(static_cast<std::int64_t>(std::ceil(p.time_s / h - 1e-9)));
  push_heading.assign(o.pushes.size(), 0.0);
  if (o.model) {
    model = *o.model;
  } else if (Status s = RobotModel::load_file(o.urdf, model); !s) {
    return s;
  }
  if (o.robot.trunk_mass_scale != 1.0 || !o.robot.trunk_com_offset_m.isZero())
    model.adjust_link(0, o.robot.trunk_mass_scale,
                      {o.robot.trunk_com_offset_m.x(), o.robot.trunk_com_offset_m.y(), 0.0});
  joint_servo.assign(model.joints().size(), -1);
  joint_tau.assign(model.joints().size(), 0.0);
  const fw::ServoTable* table = o.servo_models_from_table ? &fw::ServoTable::defaults() : nullptr;
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const int j = model.joint_index(o.servo_joints[i]);
    if (j < 0)
      return Status::error(o.urdf.string() + ": no joint '" + o.servo_joints[i] + "' for servo " +
                           std::to_string(i + 1));
    if (joint_servo[static_cast<std::size_t>(j)] >= 0)
      return Status::error("joint '" + o.servo_joints[i] + "' is mapped to two servos");
    joint_servo[static_cast<std::size_t>(j)] = static_cast<int>(i);
    servo_joint[i] = j;
    servo_models[i] = table ? (*table)[i].model : o.servo_models[i];
  }
  left_foot = model.link_index("left_foot_link");
  right_foot = model.link_index("right_foot_link");
  collision = collision_points(model);
  EngineModel& em = engine_model;
  em.robot = &model;
  em.link_mass_scale.assign(model.links().size(), 1.0);
  em.joint_armature.assign(model.joints().size(), 0.0);
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    servos[i] = make_sim_servo(o.servo.law);
    em.joint_armature[static_cast<std::size_t>(servo_joint[i])] =
        servos[i]->armature(servo_models[i], o.battery_voltage_v, o.servo);
  }
  em.left_foot = left_foot;
  em.right_foot = right_foot;
  em.contact = o.contact;
  em.ball = o.ball;
  em.gravity_mps2 = o.gravity_mps2;
  em.step_s = h;
  em.max_speed = o.max_speed;
  strength.fill(1.0);
  return Status::ok();
}

void SimWorld::Impl::draw_randomisation() {
  const Randomisation& r = options.randomise;
  EngineModel& em = engine_model;
  em.friction = options.contact.friction * (1.0 + r.friction_range * rng.uniform(-1.0, 1.0));
  for (double& s : em.link_mass_scale) s = 1.0 + r.mass_range * rng.uniform(-1.0, 1.0);
  for (double& s : strength) s = 1.0 + r.strength_range * rng.uniform(-1.0, 1.0);
  latency_ticks = options.robot.latency_ticks + (rng.uniform() < r.latency_probability ? 1 : 0);
  for (int k = 0; k < 3; ++k)
    accel_bias[k] = options.imu.accel_bias[k] + options.imu.accel_bias_std * rng.normal();
  for (int k = 0; k < 3; ++k)
    gyro_bias[k] = options.imu.gyro_bias[k] + options.imu.gyro_bias_std * rng.normal();
  // The ground: drawn (one more draw) only when its range is set (grounds.hpp).
  if (r.contact_range > 0.0) em.contact = draw_ground(options.contact, r.contact_range, rng);
  // The trunk's centre of mass: two more draws, only when its range is set.
  em.root_com_shift.setZero();
  if (r.com_range > 0.0) {
    em.root_com_shift.x() = r.com_range * rng.uniform(-1.0, 1.0);
    em.root_com_shift.y() = r.com_range * rng.uniform(-1.0, 1.0);
  }
  // The servos and the supply: one draw each, only when its bounds differ.
  friction_scale = draw_between(r.servo_friction_min, r.servo_friction_max, rng);
  torque_scale = draw_between(r.servo_torque_min, r.servo_torque_max, rng);
  supply_v = r.supply_max_v > 0.0 ? draw_between(r.supply_min_v, r.supply_max_v, rng)
                                  : options.battery_voltage_v;
}

void SimWorld::Impl::skip_reset_draws() {
  draw_randomisation();
  // reset()'s first IMU sample: the chain model draws nothing there, the plain sampler its six
  // noise values (ImuSampler::skip makes exactly those draws).
  imu.reset(options.imu, options.gravity_mps2, accel_bias, gyro_bias, Eigen::Matrix3d::Identity());
  imu.skip(rng);
}

void SimWorld::Impl::servo_torques() {
  for (std::size_t j = 0; j < joint_tau.size(); ++j) {
    const double q = engine->joint_angle(j);
    const double w = engine->joint_speed(j);
    const int servo = joint_servo[j];
    if (servo >= 0) {
      joint_tau[j] = servos[static_cast<std::size_t>(servo)]->step(q, w, h);
    } else {
      const JointSpec& spec = model.joints()[j];
      joint_tau[j] =
          -spec.damping * w - std::copysign(std::min(spec.friction, 1e-3 * std::abs(w) / h), w);
    }
  }
}

/// The force of the pushes acting during the coming step (see TorsoPush).
void SimWorld::Impl::apply_pushes() {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < options.pushes.size(); ++i) {
    const std::int64_t first = push_first_step[i];
    if (steps < first || steps >= first + push_steps) continue;
    if (steps == first) {  // the robot's heading when the push begins
      const Eigen::Matrix3d r = engine->link_pose(0).linear();
      push_heading[i] = std::atan2(r(1, 0), r(0, 0));
    }
    const double angle = push_heading[i] + options.pushes[i].direction_rad;
    const double magnitude = options.pushes[i].impulse_n_s / (static_cast<double>(push_steps) * h);
    force += magnitude * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
  }
  engine->set_torso_force(force);
}

bool SimWorld::Impl::step_once() {
  if (status != WorldStatus::kRunning) return false;
  if (!options.pushes.empty()) apply_pushes();
  servo_torques();
  // The chain reads the torso at the step's start and its acceleration over the step.
  TorsoMotion start;
  if (imu.needs_steps()) start = torso_motion();
  status = engine->step(joint_tau, reason);
  ++steps;
  if (status != WorldStatus::kRunning) return false;
  peaks.torso_accel_mps2 = std::max(peaks.torso_accel_mps2, engine->torso_acceleration().norm());
  for (std::size_t j = 0; j < joint_tau.size(); ++j) {
    if (joint_servo[j] < 0) continue;
    peaks.joint_torque_nm = std::max(peaks.joint_torque_nm, std::abs(joint_tau[j]));
    const double motor =
        std::abs(servos[static_cast<std::size_t>(joint_servo[j])]->motor_torque_nm());
    if (!(motor > peaks.servo_torque_nm)) continue;
    peaks.servo_torque_nm = motor;
    peaks.servo_index = joint_servo[j];
  }
  if (imu.needs_steps()) {
    start.linear_acceleration = engine->torso_acceleration();
    imu.feed(start, h, rng);
  }
  return true;
}

// ----------------------------------------------------------------------------------------------
SimWorld::SimWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SimWorld::~SimWorld() = default;

Status SimWorld::create(const WorldOptions& options, std::unique_ptr<SimWorld>& out) {
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  impl->rng.reseed(options.seed);
  if (Status s = impl->configure(); !s) return s;
  // reset() builds the engine (with the masses it draws) and reports a failure.
  std::unique_ptr<SimWorld> world(new SimWorld(std::move(impl)));
  if (Status s = world->reset(ResetSpec::standing()); !s) return s;
  out = std::move(world);
  return Status::ok();
}

Status SimWorld::create(const WorldOptions& options, const ResetSpec& spec,
                        std::unique_ptr<SimWorld>& out) {
  std::unique_ptr<SimWorld> world(new SimWorld(std::make_unique<Impl>()));
  if (Status s = world->restart(options, spec); !s) return s;
  out = std::move(world);
  return Status::ok();
}

Status SimWorld::restart(const WorldOptions& options, const ResetSpec& spec) {
  Impl& w = *impl_;
  w.options = options;
  w.rng.reseed(options.seed);
  if (Status s = w.configure(); !s) return s;
  w.skip_reset_draws();
  return reset(spec);
}

void SimWorld::reseed(std::uint64_t seed) {
  impl_->rng.reseed(seed);
}

Status SimWorld::reset(const ResetSpec& spec) {
  Impl& w = *impl_;
  for (double a : spec.joint_angles)
    if (!std::isfinite(a)) return Status::error("reset: non-finite joint angle");
  for (double v : spec.joint_speeds)
    if (!std::isfinite(v)) return Status::error("reset: non-finite joint speed");
  if (!std::isfinite(spec.torso_position.x()) || !std::isfinite(spec.torso_position.y()) ||
      !spec.torso_orientation.coeffs().allFinite() || !std::isfinite(spec.ball_position.x()) ||
      !std::isfinite(spec.ball_position.y()) || !spec.ball_velocity.allFinite())
    return Status::error("reset: non-finite torso or ball pose");
  w.draw_randomisation();
  EngineModel& em = w.engine_model;
  if (Status s = w.engine->build(em); !s) return Status::error("reset: " + s.message());
  // Servo parameters.
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const RobotCalibration& calibration = w.options.robot;
    ServoSetup setup;
    setup.model = w.servo_models[i];
    setup.supply_voltage_v = w.supply_v;
    setup.strength = w.strength[i] * calibration.torque_scale(w.servo_models[i]) * w.torque_scale;
    setup.friction_scale = calibration.friction_scale * w.friction_scale;
    setup.options = &w.options.servo;
    setup.joint = &w.model.joints()[static_cast<std::size_t>(w.servo_joint[i])];
    // Before the first command the servos hold the start pose at the MX's power-on P (32,
    // hal::ServoCommand's default).
    hal::ServoCommand hold;
    hold.position_rad = spec.joint_angles[i];
    hold.torque_enable = true;
    w.servos[i]->reset(setup, spec.joint_angles[i], hold);
    w.written[i] = spec.previous_commands.empty() ? hold : spec.previous_commands[0].servos[i];
    for (std::size_t k = 0; k < w.delayed.size(); ++k)
      w.delayed[k][i] = k < spec.previous_commands.size() ? spec.previous_commands[k].servos[i]
                        : spec.previous_commands.empty()  ? hold
                                                          : spec.previous_commands.back().servos[i];
  }
  w.torque_enable = true;
  // Pose.
  EngineStart start;
  start.joint_angles.assign(w.model.joints().size(), 0.0);
  for (std::size_t i = 0; i < hal::kServoCount; ++i)
    start.joint_angles[static_cast<std::size_t>(w.servo_joint[i])] = spec.joint_angles[i];
  if (std::any_of(spec.joint_speeds.begin(), spec.joint_speeds.end(),
                  [](double v) { return v != 0.0; })) {
    start.joint_speeds.assign(w.model.joints().size(), 0.0);
    for (std::size_t i = 0; i < hal::kServoCount; ++i)
      start.joint_speeds[static_cast<std::size_t>(w.servo_joint[i])] = spec.joint_speeds[i];
  }
  const double grass_top = em.contact.grass_thickness_m;
  start.ball_position = spec.ball_position;
  if (!std::isfinite(start.ball_position.z()))
    start.ball_position.z() = grass_top + w.options.ball.radius_m;
  start.ball_velocity = spec.ball_velocity;
  if (Status s = place_robot(*w.engine, w.collision, spec, w.left_foot, w.right_foot, em.contact,
                             w.model.total_mass() * w.options.gravity_mps2, start);
      !s)
    return Status::error("reset: " + s.message());
  if (spec.still_lower_foot && !start.joint_speeds.empty())
    if (Status s = still_lower_foot(*w.engine, w.left_foot, w.right_foot, start); !s)
      return Status::error("reset: " + s.message());
  w.periods = 0;
  w.steps = 0;
  w.status = WorldStatus::kRunning;
  w.reason.clear();
  // The magnetometer draws from its own generator, seeded from a copy of the world's (so its
  // draws depend on the seed and the episode but take nothing from the world's stream).
  MagnetometerStart magnetometer;
  magnetometer.position = w.engine->link_pose(0).translation();
  magnetometer.seed = WorldRng(w.rng).next_u64() ^ 0x6d61676e65746f6dULL;
  magnetometer.period_s = static_cast<double>(w.options.control_period_ns) * 1e-9;
  w.imu.reset(w.options.imu, w.options.gravity_mps2, w.accel_bias, w.gyro_bias,
              w.engine->link_pose(0).linear(), magnetometer);
  w.imu.sample(w.torso_motion(), w.rng);
  return Status::ok();
}

void SimWorld::set_servo_command(std::size_t index, const hal::ServoCommand& command) {
  if (index < hal::kServoCount) impl_->written[index] = command;
}

void SimWorld::set_torque_enable(bool enabled) {
  impl_->torque_enable = enabled;
}

hal::ServoState SimWorld::servo_state(std::size_t index) const {
  hal::ServoState out;
  if (index >= hal::kServoCount) return out;
  const Impl& w = *impl_;
  const auto joint = static_cast<std::size_t>(w.servo_joint[index]);
  const SimServo& servo = *w.servos[index];
  const hal::ServoCommand& cmd = w.written[index];
  constexpr double kSpeedUnit = 0.114 * 2.0 * M_PI / 60.0;  // present speed register unit
  out.position_rad = quantise_encoder(w.engine->joint_angle(joint));
  out.speed_rad_s = std::round(w.engine->joint_speed(joint) / kSpeedUnit) * kSpeedUnit;
  out.load = servo.load();
  out.voltage_v = w.supply_v;
  out.temperature_c = std::round(servo.temperature_c());
  out.goal_position_rad = cmd.position_rad;
  out.p_gain = cmd.p_gain;
  out.i_gain = cmd.i_gain;
  out.d_gain = cmd.d_gain;
  out.torque_limit = cmd.torque_limit;
  out.torque_enabled = cmd.torque_enable && w.torque_enable;
  out.error_flags = 0;
  out.health = hal::DeviceHealth::kOk;
  return out;
}

const ImuReading& SimWorld::imu() const {
  return impl_->imu.reading();
}

const Eigen::Vector3d& SimWorld::episode_accel_bias() const {
  return impl_->accel_bias;
}

const Eigen::Vector3d& SimWorld::episode_gyro_bias() const {
  return impl_->gyro_bias;
}

bool SimWorld::step() {
  return impl_->step_once();
}

bool SimWorld::advance_period() {
  Impl& w = *impl_;
  if (w.status != WorldStatus::kRunning) return false;
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const int d = w.latency_ticks;
    const hal::ServoCommand c =
        d == 0 ? w.written[i] : w.delayed[static_cast<std::size_t>(d - 1)][i];
    w.servos[i]->set_command(c, c.torque_enable && w.torque_enable);
    for (std::size_t k = w.delayed.size() - 1; k > 0; --k) w.delayed[k][i] = w.delayed[k - 1][i];
    w.delayed[0][i] = w.written[i];
  }
  w.peaks = {};
  for (int k = 0; k < w.steps_per_period; ++k)
    if (!w.step_once()) break;
  ++w.periods;
  if (w.status == WorldStatus::kRunning) {
    w.imu.sample(w.torso_motion(), w.rng);
  } else {
    w.imu.skip(w.rng);
  }
  return w.status == WorldStatus::kRunning;
}

const SimWorld::PeriodPeaks& SimWorld::last_period_peaks() const {
  return impl_->peaks;
}

WorldStatus SimWorld::status() const {
  return impl_->status;
}
const std::string& SimWorld::failure_reason() const {
  return impl_->reason;
}
double SimWorld::time_s() const {
  return impl_->engine->time_s();
}
std::int64_t SimWorld::period_count() const {
  return impl_->periods;
}
const WorldOptions& SimWorld::options() const {
  return impl_->options;
}
Eigen::Vector3d SimWorld::trunk_com_shift() const {
  return impl_->engine_model.root_com_shift;
}

const ContactOptions& SimWorld::ground() const {
  return impl_->engine_model.contact;
}
const RobotModel& SimWorld::model() const {
  return impl_->model;
}
double SimWorld::battery_voltage() const {
  return impl_->supply_v;
}

GroundTruth SimWorld::ground_truth() const {
  const Impl& w = *impl_;
  const PhysicsEngine& e = *w.engine;
  GroundTruth g;
  g.time_s = e.time_s();
  const ContactReport contacts = e.contacts();
  g.left_contact = contacts.left;
  g.right_contact = contacts.right;
  g.other_contacts = contacts.other_contacts;
  if (w.status == WorldStatus::kNonFinite) return g;
  g.torso = e.link_pose(0);
  g.torso_linear_velocity = e.torso_velocity();
  g.torso_angular_velocity = e.torso_angular_velocity();
  g.torso_linear_acceleration = e.torso_acceleration();
  g.center_of_mass = e.robot_center_of_mass();
  g.ball_position = e.ball_position();
  g.ball_velocity = e.ball_velocity();
  if (w.left_foot >= 0) g.left_foot = e.link_pose(static_cast<std::size_t>(w.left_foot));
  if (w.right_foot >= 0) g.right_foot = e.link_pose(static_cast<std::size_t>(w.right_foot));
  return g;
}

Eigen::Isometry3d SimWorld::torso_pose() const {
  const Impl& w = *impl_;
  if (w.status == WorldStatus::kNonFinite) return Eigen::Isometry3d::Identity();
  return w.engine->link_pose(0);
}

std::uint64_t SimWorld::state_hash() const {
  const Impl& w = *impl_;
  std::uint64_t hash = w.engine->hash(0xcbf29ce484222325ULL);
  for (std::size_t i = 0; i < hal::kServoCount; ++i) hash = w.servos[i]->hash(hash);
  return hash;
}

std::vector<Eigen::Isometry3d> SimWorld::link_poses() const {
  const Impl& w = *impl_;
  std::vector<Eigen::Isometry3d> out;
  if (w.status == WorldStatus::kNonFinite) return out;
  for (std::size_t l = 0; l < w.model.links().size(); ++l) out.push_back(w.engine->link_pose(l));
  return out;
}

std::vector<double> SimWorld::joint_angles() const {
  const Impl& w = *impl_;
  std::vector<double> out;
  for (std::size_t j = 0; j < w.model.joints().size(); ++j) out.push_back(w.engine->joint_angle(j));
  return out;
}

double SimWorld::servo_joint_angle(std::size_t index) const {
  const Impl& w = *impl_;
  if (index >= hal::kServoCount) return 0.0;
  return w.engine->joint_angle(static_cast<std::size_t>(w.servo_joint[index]));
}

void SimWorld::set_joint_speed(std::size_t joint, double speed) {
  impl_->engine->set_joint_speed(joint, speed);
}

const char* to_string(WorldStatus status) {
  switch (status) {
    case WorldStatus::kRunning:
      return "running";
    case WorldStatus::kNonFinite:
      return "non-finite state";
    case WorldStatus::kExploded:
      return "exploded";
    case WorldStatus::kIntegratorFailure:
      return "integrator failure";
  }
  return "unknown";
}

}  // namespace stride::sim
