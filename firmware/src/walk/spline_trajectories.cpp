// Spline-walk step trajectories (see spline_trajectories.hpp).
#include "stride/firmware/walk/spline_trajectories.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stride::fw::walk {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

AxisState rest(double p) {
  return {p, 0.0, 0.0};
}

}  // namespace

HipsSample nominal_hips_end(const Pose2& support, const Pose2& swing_target, const WalkVelocity& v,
                            double sway, double cycle_phase_end, const SplineWalkParameters& p,
                            double pitch) noexcept {
  const double yaw = support.theta + 0.5 * wrap_angle(swing_target.theta - support.theta);
  const double c = std::cos(yaw), s = std::sin(yaw);
  // Sway, its rate and acceleration along the heading's left axis (n = (-s, c)).
  const double omega = kTwoPi * p.frequency;
  const double angle = kTwoPi * (cycle_phase_end - p.trunk_sway_phase);
  const double lateral = sway * std::sin(angle);
  const double lateral_rate = sway * omega * std::cos(angle);
  const double lateral_acceleration = -sway * omega * omega * std::sin(angle);
  const double mid_x = 0.5 * (support.x + swing_target.x) + c * p.trunk_x_offset;
  const double mid_y = 0.5 * (support.y + swing_target.y) + s * p.trunk_x_offset;
  HipsSample end;
  end.x = {mid_x - s * lateral, c * v.x - s * (v.y + lateral_rate), -s * lateral_acceleration};
  end.y = {mid_y + c * lateral, s * v.x + c * (v.y + lateral_rate), c * lateral_acceleration};
  end.yaw = {yaw, v.turn, 0.0};
  end.pitch = rest(pitch);
  return end;
}

void StepPlan::build(const StepStart& from, const StepGoal& goal,
                     const SplineWalkParameters& p) noexcept {
  swing_ = from.swing;
  duration_ = std::max(goal.duration, 1e-3);
  swing_begin_ = std::clamp(p.double_support_ratio, 0.0, 0.9) * duration_;
  const double swing_time = duration_ - swing_begin_;
  support_ = from.support.pose;
  support_lift_ = Quintic::rest_to_rest(from.support.lift, 0.0, swing_begin_);

  // Swing foot in the plane: to the target (or past it and back).
  const Pose2 a = from.swing_foot.pose;
  const Pose2 b = goal.swing_target;
  const double yaw_b = a.theta + wrap_angle(b.theta - a.theta);  // along the shorter arc
  const double over = std::clamp(p.foot_overshoot, 0.0, 1.0);
  overshoot_time_ = duration_;
  if (over > 0.0) {
    overshoot_time_ = swing_begin_ + std::clamp(p.foot_overshoot_phase, 0.05, 0.95) * swing_time;
    const double first = overshoot_time_ - swing_begin_, second = duration_ - overshoot_time_;
    const Pose2 peak{b.x + over * (b.x - a.x), b.y + over * (b.y - a.y),
                     yaw_b + over * (yaw_b - a.theta)};
    swing_x_[0] = Quintic::rest_to_rest(a.x, peak.x, first);
    swing_y_[0] = Quintic::rest_to_rest(a.y, peak.y, first);
    swing_yaw_[0] = Quintic::rest_to_rest(a.theta, peak.theta, first);
    swing_x_[1] = Quintic::rest_to_rest(peak.x, b.x, second);
    swing_y_[1] = Quintic::rest_to_rest(peak.y, b.y, second);
    swing_yaw_[1] = Quintic::rest_to_rest(peak.theta, yaw_b, second);
  } else {
    swing_x_[0] = Quintic::rest_to_rest(a.x, b.x, swing_time);
    swing_y_[0] = Quintic::rest_to_rest(a.y, b.y, swing_time);
    swing_yaw_[0] = Quintic::rest_to_rest(a.theta, yaw_b, swing_time);
    swing_x_[1] = Quintic::hold(b.x);
    swing_y_[1] = Quintic::hold(b.y);
    swing_yaw_[1] = Quintic::hold(yaw_b);
  }

  // Swing foot height: settle in double support, rise to the apex, put down.
  apex_time_ = swing_begin_ + std::clamp(p.foot_apex_phase, 0.1, 0.9) * swing_time;
  swing_lift_[0] = Quintic::rest_to_rest(from.swing_foot.lift, 0.0, swing_begin_);
  if (goal.rise > 0.0) {
    swing_lift_[1] = Quintic::rest_to_rest(0.0, goal.rise, apex_time_ - swing_begin_);
    swing_lift_[2] = Quintic::rest_to_rest(goal.rise, -p.foot_put_down, duration_ - apex_time_);
  } else {
    swing_lift_[1] = Quintic::hold(0.0);
    swing_lift_[2] = Quintic::hold(0.0);
  }

  // Hips: from where they are to the step's end state.
  HipsSample h = from.hips;
  h.yaw.position =
      goal.hips_end.yaw.position + wrap_angle(from.hips.yaw.position - goal.hips_end.yaw.position);
  hips_x_ = Quintic::between(h.x, goal.hips_end.x, duration_);
  hips_y_ = Quintic::between(h.y, goal.hips_end.y, duration_);
  hips_yaw_ = Quintic::between(h.yaw, goal.hips_end.yaw, duration_);
  hips_pitch_ = Quintic::between(h.pitch, goal.hips_end.pitch, duration_);
}

StepSample StepPlan::sample(double t) const noexcept {
  StepSample out;
  t = std::clamp(t, 0.0, duration_);
  out.phase = t / duration_;
  FootSample support{support_, support_lift_.position(t)};
  FootSample swing;
  const int xy = t < overshoot_time_ ? 0 : 1;
  const double txy = xy == 0 ? t - swing_begin_ : t - overshoot_time_;
  swing.pose = {swing_x_[xy].position(txy), swing_y_[xy].position(txy),
                wrap_angle(swing_yaw_[xy].position(txy))};
  if (t < swing_begin_) {
    swing.lift = swing_lift_[0].position(t);
  } else if (t < apex_time_) {
    swing.lift = swing_lift_[1].position(t - swing_begin_);
  } else {
    swing.lift = swing_lift_[2].position(t - apex_time_);
  }
  const bool single_support = t >= swing_begin_ && t < duration_;
  if (swing_ == Foot::kLeft) {
    out.left = swing;
    out.right = support;
    out.left_down = !single_support;
  } else {
    out.right = swing;
    out.left = support;
    out.right_down = !single_support;
  }
  out.hips.x = hips_x_.at(t);
  out.hips.y = hips_y_.at(t);
  out.hips.yaw = hips_yaw_.at(t);
  out.hips.yaw.position = wrap_angle(out.hips.yaw.position);
  out.hips.pitch = hips_pitch_.at(t);
  return out;
}

}  // namespace stride::fw::walk
