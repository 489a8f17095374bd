// WalkEngine: state machine, step planning and per-tick target generation (see the header and
// firmware/walk/README.md).
#include "stride/firmware/walk/walk_engine.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "stride/firmware/stand_pose.hpp"
#include "stride/firmware/walk/arm_swing.hpp"
#include "stride/firmware/walk/swing_foot.hpp"

namespace stride::fw {
namespace {

using walk::Foot;
using walk::Pose2;

}  // namespace

WalkEngine::WalkEngine(ParameterStore& store, const ServoTable& servos, std::int64_t period_ns,
                       const AttitudeEstimator& attitude, const RobotDescription& robot)
    : parameter_set_(store),
      servos_(servos, "walk engine"),
      period_s_(static_cast<double>(period_ns) * 1e-9),
      attitude_(attitude),
      balance_(store, period_s_),
      heading_(store, period_s_),
      compliance_(store, robot, servos, period_s_),
      capture_(store, period_s_) {
  if (period_ns <= 0) throw std::invalid_argument("walk engine: control period must be > 0");
  parameter_set_.read(params_);
  reset_stance();
}

void WalkEngine::reset_stance() noexcept {
  const double half_width = walk::nominal_foot_offset(params_).y;
  left_destination_ = {0.0, half_width, 0.0};
  right_destination_ = {0.0, -half_width, 0.0};
  left_source_ = left_destination_;
  right_source_ = right_destination_;
  torso_destination_ = walk::torso_between(left_destination_, right_destination_, params_);
  torso_source_ = torso_destination_;
  support_ = torso_destination_;
  swing_ = Foot::kRight;
  velocity_ = {};
  step_count_ = 0;
}

void WalkEngine::start(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
                       hal::Tick tick) noexcept {
  parameter_set_.read(params_);
  reset_stance();
  state_ = State::kStarting;
  stop_requested_ = false;
  start_tick_ = tick;
  step_begin_s_ = 0.0;
  balance_.reset();
  heading_.reset();
  compliance_.reset();
  capture_.reset();
  heading_correction_ = 0.0;
  std::array<double, hal::kServoCount> pose{};
  servos_.start_pose(sensors, last_sent, blend_from_, pose);
  adopt_stance(pose);
}

void WalkEngine::adopt_stance(const std::array<double, hal::kServoCount>& pose) noexcept {
  // Where the feet are now (forward kinematics of the pose being held), projected into the
  // walk plane with the torso reference point at the origin: the walk starts from these feet
  // (the start blend moves only the torso), so nothing has to slide while both feet are down.
  const Eigen::Matrix3d trunk = walk::trunk_rotation(0.0, params_.body_tilt);
  const Eigen::Vector3d reference(walk::LegGeometry::kHipX, 0.0,
                                  walk::LegGeometry::kHipZ + kTorsoAboveHip);
  const Pose2 left =
      walk::WalkServos::foot_in_plane(left_leg_, pose, servos_.left_leg, trunk, reference);
  const Pose2 right =
      walk::WalkServos::foot_in_plane(right_leg_, pose, servos_.right_leg, trunk, reference);
  const bool plausible = walk::WalkServos::plausible_stance(left, right);
  if (!plausible) return;  // keep the nominal stance of reset_stance()
  left_destination_ = left_source_ = left;
  right_destination_ = right_source_ = right;
  torso_destination_ = walk::torso_between(left, right, params_);
  torso_source_ = torso_destination_;
  support_ = torso_destination_;
}

bool WalkEngine::done() const noexcept {
  return state_ == State::kStopped;
}

void WalkEngine::set_velocity(double vx, double vy, double vtheta) noexcept {
  command_ = {vx, vy, vtheta};  // scaled (NaN -> 0, clamped) at each step start
}

void WalkEngine::request_stop() noexcept {
  stop_requested_ = true;
  if (state_ == State::kWalking) state_ = State::kStopRequest;
}

void WalkEngine::begin_step() noexcept {
  parameter_set_.read(params_);
  ++step_count_;
  const auto target = walk::scale_command(command_, params_);
  velocity_ = walk::accelerate(velocity_, target, params_.step_time, params_);
  if (step_count_ <= kStepsWithoutLift) velocity_ = {};
  // The heading hold turns the step back towards the held heading (only once the feet lift).
  const double correction = heading_.begin_step();
  heading_correction_ = step_count_ > kStepsWithoutLift ? correction : 0.0;
  walk::PlanarVector planned = velocity_;
  planned.angle += heading_correction_;
  // Capture step: the footstep moves with the capture point's deviation (torso frame, turned
  // into the walk plane). The swing target moves by 1.5 v (v, then the torso's half step).
  if (step_count_ > kStepsWithoutLift && capture_.footstep_enabled()) {
    const double c = std::cos(torso_destination_.theta), s = std::sin(torso_destination_.theta);
    const double dx = capture_.step_offset_x(), dy = capture_.step_offset_y();
    planned.x += (c * dx - s * dy) / 1.5;
    planned.y += (s * dx + c * dy) / 1.5;
  }
  left_source_ = left_destination_;
  right_source_ = right_destination_;
  torso_source_ = torso_destination_;
  if (state_ == State::kLastStep) {
    state_ = State::kStopped;
    velocity_ = {};
    return;
  }
  // The first step swings the foot on the side the walk is commanded to (the left foot when
  // there is no sideways command), so walking right mirrors walking left.
  if (step_count_ == 1 && target.y < 0.0) swing_ = Foot::kLeft;
  swing_ = walk::other(swing_);
  const bool left_swings = swing_ == Foot::kLeft;
  const Pose2& support_foot = left_swings ? right_source_ : left_source_;
  Pose2& swing_destination = left_swings ? left_destination_ : right_destination_;
  const Pose2& swing_source = left_swings ? left_source_ : right_source_;
  if (state_ == State::kStopRequest) {
    state_ = State::kLastStep;
    velocity_ = {};
    swing_destination = walk::plan_closing_step(swing_, support_foot, params_);
  } else {
    swing_destination =
        walk::plan_swing_destination(swing_, swing_source, support_foot, planned, params_);
  }
  torso_destination_ = walk::torso_between(left_destination_, right_destination_, params_);
  support_ = walk::support_point(walk::other(swing_), support_foot, params_);
  // Right after the start the ZMP excursion may ramp in (walk.balance.start_sway_steps).
  const double sway = balance_.start_sway_scale(step_count_);
  if (sway < 1.0) {
    const double mid_x = 0.5 * (torso_source_.x + torso_destination_.x);
    const double mid_y = 0.5 * (torso_source_.y + torso_destination_.y);
    support_.x = mid_x + sway * (support_.x - mid_x);
    support_.y = mid_y + sway * (support_.y - mid_y);
  }
  const auto& p = params_;
  lipm_x_.solve(torso_source_.x, torso_destination_.x, support_.x, p.step_time, p.zmp_time,
                p.single_support_start, p.single_support_end);
  lipm_y_.solve(torso_source_.y, torso_destination_.y, support_.y, p.step_time, p.zmp_time,
                p.single_support_start, p.single_support_end);
}

void WalkEngine::step(const hal::SensorFrame& sensors, hal::Tick tick,
                      hal::CommandFrame& out) noexcept {
  tick_clamped_ = false;
  balance_shift_ = balance_.update(attitude_);
  // The heading hold learns the gyro bias while the start blend stands, then holds the heading
  // while no turn is commanded (a NaN command counts as 0, as in scale_command).
  const bool holding = !(std::abs(command_.angle) > 0.0);
  heading_.update(attitude_, sensors.cm730, state_ == State::kStarting, holding);
  const bool stepping =
      state_ == State::kWalking || state_ == State::kStopRequest || state_ == State::kLastStep;
  const double pair_phase =
      0.5 * ((swing_ == walk::Foot::kLeft ? 0.0 : 1.0) + std::clamp(snapshot_.phase, 0.0, 1.0));
  capture_.update(attitude_, pair_phase, params_.step_time,
                  stepping && step_count_ > kStepsWithoutLift, !stepping);
  const double t = static_cast<double>(std::max<hal::Tick>(0, tick - start_tick_)) * period_s_;
  double blend = 1.0;
  if (state_ == State::kStarting) {
    if (t < kStartBlendTime) {
      const double u = t / kStartBlendTime;
      blend = u * u * (3.0 - 2.0 * u);
    } else {
      state_ = stop_requested_ ? State::kStopped : State::kWalking;
      if (state_ == State::kWalking) {
        step_begin_s_ = 0.0;
        begin_step();
      }
    }
  }
  if (state_ == State::kWalking || state_ == State::kStopRequest || state_ == State::kLastStep) {
    const double walking_time = t - kStartBlendTime;
    // Step timing feedback: the step's clock runs at the phase rate (exactly the tick clock
    // when the feedback is off, so the seed's walk is bit-identical).
    snapshot_.phase_rate = 1.0;
    if (capture_.timing_enabled() && step_count_ > kStepsWithoutLift) {
      snapshot_.phase_rate = capture_.phase_rate(swing_ == walk::Foot::kLeft);
      step_begin_s_ -= (snapshot_.phase_rate - 1.0) * period_s_;
    }
    double time_in_step = walking_time - step_begin_s_;
    // Support exchange at touchdown: a swing foot that has landed ends its step now.
    if (step_count_ > kStepsWithoutLift && state_ != State::kLastStep &&
        time_in_step < params_.step_time) {
      const auto& knee =
          sensors.servos[swing_ == walk::Foot::kLeft ? servos_.left_leg[3] : servos_.right_leg[3]];
      if (capture_.touchdown(time_in_step / params_.step_time, knee.load)) {
        step_begin_s_ -= params_.step_time - time_in_step;
        time_in_step = params_.step_time;
        ++touchdown_steps_;
      }
    }
    for (int guard = 0; guard < 8 && time_in_step >= params_.step_time; ++guard) {
      step_begin_s_ += params_.step_time;
      begin_step();
      if (state_ == State::kStopped) break;
      time_in_step = walking_time - step_begin_s_;
    }
    if (state_ == State::kStopped) {
      compute_targets(0.0, true);
    } else {
      compute_targets(std::clamp(time_in_step, 0.0, params_.step_time), false);
    }
  } else {
    compute_targets(0.0, true);
  }
  if (tick_clamped_) ++ik_clamped_ticks_;
  snapshot_.ik_clamped = tick_clamped_;
  snapshot_.state = state_;
  snapshot_.step_count = step_count_;
  snapshot_.swing = swing_;
  snapshot_.support_point = support_;
  snapshot_.velocity = velocity_;
  snapshot_.heading_correction = heading_correction_;
  snapshot_.heading_error = heading_.heading_error();
  snapshot_.capture_x = capture_.deviation_x();
  snapshot_.capture_y = capture_.deviation_y();

  const double arm_gain = gain_to_p_register(params_.gain_arms);
  const double leg_gain = gain_to_p_register(params_.gain_legs);
  if (compliance_.enabled())
    compliance_.apply(targets_, field_, contact_, servos_.p_gains(arm_gain, leg_gain), sensors);
  servos_.write(targets_, blend_from_, blend, arm_gain, leg_gain, out);
  out.tick = tick;
}

void WalkEngine::compute_targets(double time_in_step, bool standing) noexcept {
  const auto& p = params_;
  Pose2 left = left_destination_;
  Pose2 right = right_destination_;
  Pose2 torso;
  double phase = 0.5;
  double left_lift = 0.0;
  double right_lift = 0.0;
  double left_roll = 0.0;
  double right_roll = 0.0;
  double swing_feedback = 1.0;  // share of the balance shift the swing leg takes
  contact_ = {true, true};
  Eigen::Vector2d acceleration = Eigen::Vector2d::Zero();  // planned, walk plane [m/s^2]
  if (standing) {
    torso = walk::torso_between(left, right, p);
  } else {
    phase = std::clamp(time_in_step / p.step_time, 0.0, 1.0);
    torso = walk::interpolate(torso_source_, torso_destination_, phase);
    torso.x = lipm_x_.position(time_in_step);
    torso.y = lipm_y_.position(time_in_step);
    const auto profile = walk::swing_profile(phase, p.single_support_start, p.single_support_end);
    const double lift = step_count_ > kStepsWithoutLift
                            ? p.step_height * profile.vertical * walk::lift_factor(velocity_, p)
                            : 0.0;
    const double compensation = p.hip_roll_compensation * profile.compensation;
    acceleration = {lipm_x_.acceleration(time_in_step), lipm_y_.acceleration(time_in_step)};
    const double psi = profile.single_support_phase;
    if (psi > 0.0 && psi < 1.0 && step_count_ > kStepsWithoutLift) {
      contact_.left = swing_ != Foot::kLeft;
      contact_.right = swing_ != Foot::kRight;
    }
    swing_feedback = balance_.double_support_weight() * (1.0 - profile.compensation);
    if (swing_ == Foot::kLeft) {
      left = walk::interpolate(left_source_, left_destination_, profile.horizontal);
      right = right_source_;
      left_lift = lift;
      right_roll = -compensation;
    } else {
      right = walk::interpolate(right_source_, right_destination_, profile.horizontal);
      left = left_source_;
      right_lift = lift;
      left_roll = compensation;
    }
  }
  // The support leg takes the balance feedback (both legs while standing; the swing leg a share
  // while both feet are down, walk.balance.double_support_weight).
  const double left_feedback = standing || swing_ == Foot::kRight ? 1.0 : swing_feedback;
  const double right_feedback = standing || swing_ == Foot::kLeft ? 1.0 : swing_feedback;
  solve_leg(left_leg_, left, left_lift, torso, left_roll, left_feedback, servos_.left_leg);
  solve_leg(right_leg_, right, right_lift, torso, right_roll, right_feedback, servos_.right_leg);
  write_arms(phase, torso, left, right);
  const Eigen::Matrix3d trunk = walk::trunk_rotation(torso.theta, p.body_tilt);
  field_ = trunk.transpose() * Eigen::Vector3d(-acceleration.x(), -acceleration.y(), -9.81);
  snapshot_.phase = phase;
  snapshot_.torso = torso;
  snapshot_.left_foot = left;
  snapshot_.right_foot = right;
  snapshot_.left_lift = left_lift;
  snapshot_.right_lift = right_lift;
}

void WalkEngine::solve_leg(const walk::LegKinematics& leg, const Pose2& foot, double lift,
                           const Pose2& torso, double hip_roll_offset, double feedback,
                           const std::array<std::size_t, 6>& servo_index) noexcept {
  const Eigen::Matrix3d trunk_rotation = walk::trunk_rotation(torso.theta, params_.body_tilt);
  const Eigen::Vector3d torso_position(torso.x, torso.y, params_.body_height);
  const Eigen::Vector3d ankle(foot.x, foot.y, lift + walk::LegGeometry::kAnkleHeight);
  const Eigen::Vector3d reference(walk::LegGeometry::kHipX, 0.0,
                                  walk::LegGeometry::kHipZ + kTorsoAboveHip);
  walk::Pose3 target;
  target.position = reference + trunk_rotation.transpose() * (ankle - torso_position);
  target.rotation = trunk_rotation.transpose() *
                    Eigen::AngleAxisd(foot.theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const walk::LegIkResult ik = leg.inverse(target);
  tick_clamped_ = tick_clamped_ || ik.clamped;
  walk::LegJoints q = ik.joints;
  q.hip_roll += hip_roll_offset;
  walk::add_balance_shift(q, balance_shift_, feedback);
  walk::WalkServos::set_leg(targets_, servo_index, q);
}

void WalkEngine::write_arms(double phase, const Pose2& torso, const Pose2& left_foot,
                            const Pose2& right_foot) noexcept {
  const auto arms = walk::arm_swing(phase, swing_, walk::relative(torso, left_foot),
                                    walk::relative(torso, right_foot), params_);
  // Table E arm pitches are NUbots angles: URDF shoulder pitch = NUbots - pi/2 (igus.md 1.5).
  constexpr double kPitchOffset = std::numbers::pi / 2.0;
  targets_[servos_.left_arm[0]] = arms.left.pitch - kPitchOffset;
  targets_[servos_.left_arm[1]] = arms.left.roll;
  targets_[servos_.left_arm[2]] = arms.left.elbow;
  targets_[servos_.right_arm[0]] = arms.right.pitch - kPitchOffset;
  targets_[servos_.right_arm[1]] = arms.right.roll;
  targets_[servos_.right_arm[2]] = arms.right.elbow;
}

}  // namespace stride::fw
