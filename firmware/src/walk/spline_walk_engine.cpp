// SplineWalkEngine: state machine, step planning and per-tick targets (design in the header,
// equations and figures in SPLINE_WALK.md).
#include "stride/firmware/walk/spline_walk_engine.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "stride/firmware/stand_pose.hpp"

namespace stride::fw {
namespace {

using walk::Foot;
using walk::Pose2;

// The hips' midpoint in the trunk frame (the hip roll/pitch crossings at zero yaw).
const Eigen::Vector3d kHipsInTrunk(walk::LegGeometry::kHipX, 0.0, walk::LegGeometry::kHipZ);

// Largest phase-rate change the timing feedback may make (either way).
constexpr double kMaxRateChange = 0.6;

// The swing leg's share of the balance feedback over a step (u the step's phase, d its double
// support ratio): from 1 (it was the support leg) to `share` over the double support, to 0
// over the first fifth of the swing, and back to 1 over the last fifth (it lands as the
// support leg), so that neither leg's feedback jumps when a step ends by the clock.
double swing_leg_feedback(double u, double d, double share) {
  if (u < d) return 1.0 - (1.0 - share) * (u / d);
  const double s = (u - d) / std::max(1e-6, 1.0 - d);  // phase of the swing
  if (s < 0.2) return share * (1.0 - s / 0.2);
  if (s > 0.8) return std::min(1.0, (s - 0.8) / 0.2);
  return 0.0;
}

// The support leg's share: from what the leg had when it landed (`landed`, below 1 when a
// touchdown ended the step early) to 1 over the double support (at least a tenth of the step).
double support_leg_feedback(double u, double d, double landed) {
  return landed + (1.0 - landed) * std::min(1.0, u / std::max(d, 0.1));
}

}  // namespace

SplineWalkEngine::SplineWalkEngine(ParameterStore& store, const ServoTable& servos,
                                   std::int64_t period_ns, const AttitudeEstimator& attitude,
                                   const RobotDescription& robot)
    : parameter_set_(store),
      servos_(servos, "spline walk"),
      period_s_(static_cast<double>(period_ns) * 1e-9),
      attitude_(attitude),
      balance_(store, period_s_, "walk.spline"),
      heading_(store, period_s_, "walk.spline"),
      compliance_(store, robot, servos, period_s_, "walk.spline"),
      capture_(store, period_s_, "walk.spline") {
  if (period_ns <= 0) throw std::invalid_argument("spline walk: control period must be > 0");
  parameter_set_.read(params_);
}

void SplineWalkEngine::start(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
                             hal::Tick tick) noexcept {
  parameter_set_.read(params_);
  state_ = State::kStarting;
  start_tick_ = tick;
  step_count_ = 0;
  time_in_step_ = 0.0;
  velocity_ = {};
  balance_.reset();
  heading_.reset();
  compliance_.reset();
  capture_.reset();
  std::array<double, hal::kServoCount> pose{};
  servos_.start_pose(sensors, last_sent, blend_from_, pose);
  adopt_feet(pose);
}

void SplineWalkEngine::adopt_feet(const std::array<double, hal::kServoCount>& pose) noexcept {
  // The walk starts on the feet where they stand (forward kinematics of the pose held, the
  // hips at the origin of the walk plane), so nothing slides while the stance blends in.
  const Eigen::Matrix3d trunk = walk::trunk_rotation(0.0, params_.trunk_pitch);
  Pose2 left =
      walk::WalkServos::foot_in_plane(left_leg_, pose, servos_.left_leg, trunk, kHipsInTrunk);
  Pose2 right =
      walk::WalkServos::foot_in_plane(right_leg_, pose, servos_.right_leg, trunk, kHipsInTrunk);
  const bool plausible = walk::WalkServos::plausible_stance(left, right);
  if (!plausible) {
    left = {0.0, 0.5 * params_.foot_distance, 0.0};
    right = {0.0, -0.5 * params_.foot_distance, 0.0};
  }
  walk::StepStart from;
  from.swing = Foot::kLeft;
  from.swing_foot = {left, 0.0};
  from.support = {right, 0.0};
  walk::StepGoal goal;
  goal.swing_target = left;
  goal.duration = 0.5 / params_.frequency;
  goal.hips_end = walk::nominal_hips_end(right, left, {}, 0.0, 1.0, params_, params_.trunk_pitch);
  from.hips = goal.hips_end;
  plan_.build(from, goal, params_);
  sample_ = plan_.sample(plan_.duration());
}

void SplineWalkEngine::set_velocity(double vx, double vy, double vtheta) noexcept {
  command_ = {vx, vy, vtheta};  // checked (NaN -> 0, clamped) at each step's start
}

void SplineWalkEngine::request_stop() noexcept {
  if (state_ == State::kStarting) {
    state_ = State::kStopped;
  } else if (state_ == State::kWalking) {
    state_ = State::kStopping;
  }
}

void SplineWalkEngine::begin_step() noexcept {
  // The leg that lands keeps the feedback share it had (less than 1 after an early touchdown).
  landed_feedback_ = step_count_ == 0
                         ? 1.0
                         : swing_leg_feedback(sample_.phase, params_.double_support_ratio,
                                              balance_.double_support_weight());
  parameter_set_.read(params_);
  const auto& p = params_;
  const double duration = 0.5 / p.frequency;
  const Foot landed = plan_.swing();
  // The foot that just landed takes the weight; the other one swings.
  walk::StepStart from;
  // The first step swings the foot on the side the walk is commanded to (the left one when no
  // sideways command), so walking right mirrors walking left.
  if (step_count_ == 0) {
    from.swing = command_.y < 0.0 ? Foot::kRight : Foot::kLeft;
  } else {
    from.swing = walk::other(landed);
  }
  from.support = from.swing == Foot::kLeft ? sample_.right : sample_.left;
  from.swing_foot = from.swing == Foot::kLeft ? sample_.left : sample_.right;
  from.hips = sample_.hips;
  ++step_count_;

  const bool in_place = static_cast<double>(step_count_) <= p.start_steps;
  const double ramp =
      p.start_steps > 0.0 ? std::min(1.0, static_cast<double>(step_count_) / p.start_steps) : 1.0;
  walk::WalkVelocity target{};
  if (state_ == State::kWalking && !in_place) target = walk::command_velocity(command_, p);
  velocity_ = walk::accelerate(velocity_, target, duration, p);
  const double correction = heading_.begin_step();
  const double extra_turn = in_place ? 0.0 : correction;

  walk::StepGoal goal;
  goal.duration = duration;
  const bool slow = std::abs(velocity_.x) < 0.02 && std::abs(velocity_.y) < 0.02 &&
                    std::abs(velocity_.turn) < 0.1;
  if (state_ == State::kStopping && slow) state_ = State::kLastStep;
  const double pitch = p.trunk_pitch + p.trunk_pitch_vx * velocity_.x;
  if (state_ == State::kLastStep) {
    velocity_ = {};
    goal.swing_target = walk::plan_spline_closing_step(from.swing, from.support.pose, p);
    goal.rise = p.foot_rise;
    goal.hips_end =
        walk::nominal_hips_end(from.support.pose, goal.swing_target, {}, 0.0, 0.0, p, pitch);
  } else {
    // The capture step's offset (trunk frame; the step's frame is within a few degrees of it).
    walk::PlanarVector offset;
    if (!in_place && capture_.footstep_enabled())
      offset = {capture_.step_offset_x(), capture_.step_offset_y(), 0.0};
    goal.swing_target = walk::plan_spline_step(from.swing, from.support.pose, velocity_, duration,
                                               extra_turn, offset, p);
    goal.rise = p.foot_rise * ramp;
    const double sway =
        ramp * std::max(0.0, p.trunk_sway + p.trunk_sway_vy * std::abs(velocity_.y));
    // The cycle's phase is 0 when the left foot takes the weight (the right one swings).
    const double phase_end = from.swing == Foot::kRight ? 0.5 : 1.0;
    goal.hips_end = walk::nominal_hips_end(from.support.pose, goal.swing_target, velocity_, sway,
                                           phase_end, p, pitch);
  }
  plan_.build(from, goal, p);
  time_in_step_ = 0.0;
}

void SplineWalkEngine::step(const hal::SensorFrame& sensors, hal::Tick tick,
                            hal::CommandFrame& out) noexcept {
  tick_clamped_ = false;
  balance_shift_ = balance_.update(attitude_);
  const bool holding = !(std::abs(command_.angle) > 0.0);
  heading_.update(attitude_, sensors.cm730, state_ == State::kStarting, holding);
  const double t = static_cast<double>(std::max<hal::Tick>(0, tick - start_tick_)) * period_s_;
  double blend = 1.0;
  if (state_ == State::kStarting) {
    if (t < kStartBlendTime) {
      const double u = t / kStartBlendTime;
      blend = u * u * (3.0 - 2.0 * u);
    } else {
      state_ = State::kWalking;
      begin_step();
    }
  }
  const bool stepping =
      state_ == State::kWalking || state_ == State::kStopping || state_ == State::kLastStep;
  const double pair_phase = 0.5 * ((plan_.swing() == Foot::kLeft ? 0.0 : 1.0) + sample_.phase);
  capture_.update(attitude_, pair_phase, plan_.duration(),
                  stepping && static_cast<double>(step_count_) > params_.start_steps, !stepping);
  if (stepping) walk_tick(sensors);
  compute_targets(sample_);
  if (tick_clamped_) ++ik_clamped_ticks_;

  snapshot_.state = state_;
  snapshot_.phase = sample_.phase;
  snapshot_.step_count = step_count_;
  snapshot_.swing = plan_.swing();
  snapshot_.hips = {sample_.hips.x.position, sample_.hips.y.position, sample_.hips.yaw.position};
  snapshot_.left_foot = sample_.left.pose;
  snapshot_.right_foot = sample_.right.pose;
  snapshot_.left_lift = sample_.left.lift;
  snapshot_.right_lift = sample_.right.lift;
  snapshot_.velocity = velocity_;
  snapshot_.ik_clamped = tick_clamped_;

  const double arm_gain = gain_to_p_register(params_.gain_arms);
  const double leg_gain = gain_to_p_register(params_.gain_legs);
  if (compliance_.enabled())
    compliance_.apply(targets_, field_, contact_, servos_.p_gains(arm_gain, leg_gain), sensors);
  servos_.write(targets_, blend_from_, blend, arm_gain, leg_gain, out);
  out.tick = tick;
}

void SplineWalkEngine::walk_tick(const hal::SensorFrame& sensors) noexcept {
  const auto& p = params_;
  const bool moving = static_cast<double>(step_count_) > p.start_steps;
  // Step timing: the phase runs faster while the capture point leaves towards the swing side
  // (the roll) or along x (the pitch).
  double rate = 1.0;
  if (moving) {
    rate = capture_.phase_rate(plan_.swing() == Foot::kLeft);
    rate += p.timing_gain_pitch * std::abs(capture_.deviation_x());
    rate = std::clamp(rate, 1.0 - kMaxRateChange, 1.0 + kMaxRateChange);
  }
  snapshot_.phase_rate = rate;
  time_in_step_ += rate * period_s_;
  // Step end at touchdown: a swing foot that carries load late in the step ends it now.
  bool ended = time_in_step_ >= plan_.duration();
  if (!ended && moving && state_ != State::kLastStep) {
    const auto& knee =
        sensors.servos[plan_.swing() == Foot::kLeft ? servos_.left_leg[3] : servos_.right_leg[3]];
    if (capture_.touchdown(time_in_step_ / plan_.duration(), knee.load)) {
      ended = true;
      ++touchdown_steps_;
    }
  }
  if (ended) {
    sample_ = plan_.sample(std::min(time_in_step_, plan_.duration()));
    if (state_ == State::kLastStep) {
      state_ = State::kStopped;
      velocity_ = {};
      return;
    }
    begin_step();
  }
  sample_ = plan_.sample(time_in_step_);
}

void SplineWalkEngine::compute_targets(const walk::StepSample& sample) noexcept {
  const bool left_swings = plan_.swing() == Foot::kLeft;
  contact_ = {sample.left_down, sample.right_down};
  // The support leg takes the balance feedback; the legs hand it over without a jump.
  const double swing_feedback = swing_leg_feedback(sample.phase, params_.double_support_ratio,
                                                   balance_.double_support_weight());
  const double support_feedback =
      support_leg_feedback(sample.phase, params_.double_support_ratio, landed_feedback_);
  const bool standing = state_ == State::kStopped || state_ == State::kStarting;
  const double left_feedback = standing ? 1.0 : (left_swings ? swing_feedback : support_feedback);
  const double right_feedback = standing ? 1.0 : (left_swings ? support_feedback : swing_feedback);
  solve_leg(left_leg_, sample.left, sample.hips, left_feedback, servos_.left_leg);
  solve_leg(right_leg_, sample.right, sample.hips, right_feedback, servos_.right_leg);

  // Arms: the stand pose's, each shoulder swinging with the opposite foot's advance.
  const double c = std::cos(sample.hips.yaw.position), s = std::sin(sample.hips.yaw.position);
  auto advance = [&](const walk::FootSample& foot) {
    return c * (foot.pose.x - sample.hips.x.position) + s * (foot.pose.y - sample.hips.y.position);
  };
  const double swing = params_.arm_swing;
  targets_[servos_.left_arm[0]] =
      kStandPoseRad[servos_.left_arm[0]] - swing * advance(sample.right);
  targets_[servos_.right_arm[0]] =
      kStandPoseRad[servos_.right_arm[0]] - swing * advance(sample.left);
  for (std::size_t j = 1; j < 3; ++j) {
    targets_[servos_.left_arm[j]] = kStandPoseRad[servos_.left_arm[j]];
    targets_[servos_.right_arm[j]] = kStandPoseRad[servos_.right_arm[j]];
  }
  // Gravity less the hips' planned acceleration, in the trunk frame (compliance feed-forward).
  const Eigen::Matrix3d trunk =
      walk::trunk_rotation(sample.hips.yaw.position, sample.hips.pitch.position);
  field_ = trunk.transpose() *
           Eigen::Vector3d(-sample.hips.x.acceleration, -sample.hips.y.acceleration, -9.81);
}

void SplineWalkEngine::solve_leg(const walk::LegKinematics& leg, const walk::FootSample& foot,
                                 const walk::HipsSample& hips, double feedback,
                                 const std::array<std::size_t, 6>& servo_index) noexcept {
  const Eigen::Matrix3d trunk = walk::trunk_rotation(hips.yaw.position, hips.pitch.position);
  const Eigen::Vector3d hips_position(hips.x.position, hips.y.position, params_.trunk_height);
  const Eigen::Vector3d ankle(foot.pose.x, foot.pose.y,
                              foot.lift + walk::LegGeometry::kAnkleHeight);
  walk::Pose3 target;
  target.position = kHipsInTrunk + trunk.transpose() * (ankle - hips_position);
  target.rotation = trunk.transpose() *
                    Eigen::AngleAxisd(foot.pose.theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const walk::LegIkResult ik = leg.inverse(target);
  tick_clamped_ = tick_clamped_ || ik.clamped;
  walk::LegJoints q = ik.joints;
  walk::add_balance_shift(q, balance_shift_, feedback);
  walk::WalkServos::set_leg(targets_, servo_index, q);
}

}  // namespace stride::fw
