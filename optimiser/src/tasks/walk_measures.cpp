// Walk measures from ground truth (definitions in walk_measures.hpp).
#include "stride/optimiser/tasks/walk_measures.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stride::opt {

double torso_yaw(const Eigen::Isometry3d& torso) {
  return std::atan2(torso.linear()(1, 0), torso.linear()(0, 0));
}

void YawTracker::reset(double yaw) {
  last_ = unwrapped_ = yaw;
}

double YawTracker::update(double yaw) {
  double delta = yaw - last_;
  delta = std::remainder(delta, 2.0 * std::numbers::pi);
  unwrapped_ += delta;
  last_ = yaw;
  return unwrapped_;
}

PlanarPose walking_frame(const sim::GroundTruth& truth, double yaw) {
  const Eigen::Vector3d mid =
      0.5 * (truth.left_foot.translation() + truth.right_foot.translation());
  return {mid.x(), mid.y(), yaw};
}

double Translation::drift_ratio() const {
  return off_axis_m / std::max(std::abs(along_m), kDriftDistanceFloor);
}

Translation measure_translation(const PlanarPose& a, const PlanarPose& b, double ux, double uy) {
  const double c = std::cos(a.yaw), s = std::sin(a.yaw);
  const double dx = b.x - a.x, dy = b.y - a.y;
  // The displacement in a's heading frame.
  const double fx = c * dx + s * dy, fy = -s * dx + c * dy;
  Translation t;
  t.along_m = fx * ux + fy * uy;
  t.off_axis_m = std::abs(-fx * uy + fy * ux);
  t.heading_change_rad = std::abs(b.yaw - a.yaw);
  t.distance_m = std::hypot(dx, dy);
  return t;
}

double limit_violation(double value, double limit, double scale) {
  if (limit < 0.0) return 0.0;
  return std::min(0.0, (limit - value) * scale);
}

const char* to_string(OmniDirection direction) {
  switch (direction) {
    case OmniDirection::kForward:
      return "forward";
    case OmniDirection::kBackward:
      return "backward";
    case OmniDirection::kLeft:
      return "left";
    case OmniDirection::kRight:
      return "right";
    case OmniDirection::kTurnLeft:
      return "turn_left";
    case OmniDirection::kTurnRight:
      return "turn_right";
  }
  return "?";
}

std::array<double, 3> omni_command(OmniDirection direction) {
  switch (direction) {
    case OmniDirection::kForward:
      return {1.0, 0.0, 0.0};
    case OmniDirection::kBackward:
      return {-1.0, 0.0, 0.0};
    case OmniDirection::kLeft:
      return {0.0, 1.0, 0.0};
    case OmniDirection::kRight:
      return {0.0, -1.0, 0.0};
    case OmniDirection::kTurnLeft:
      return {0.0, 0.0, 1.0};
    case OmniDirection::kTurnRight:
      return {0.0, 0.0, -1.0};
  }
  return {0.0, 0.0, 0.0};
}

namespace {

bool is_turn(int segment) {
  return segment >= static_cast<int>(OmniDirection::kTurnLeft);
}

}  // namespace

OmniEpisode::OmniEpisode(const OmniTiming& timing, double period_s)
    : timing_(timing), period_s_(period_s) {}

std::array<double, 3> OmniEpisode::command(hal::Tick tick) const {
  const double t = static_cast<double>(tick) * period_s_ - timing_.start_s;
  const double length = timing_.ramp_s + timing_.hold_s + timing_.stop_s;
  if (t < 0.0 || length <= 0.0) return {0.0, 0.0, 0.0};
  const int segment = static_cast<int>(std::floor(t / length));
  if (segment >= kOmniSegments) return {0.0, 0.0, 0.0};
  const double in_segment = t - segment * length;
  double scale = 0.0;
  if (in_segment < timing_.ramp_s) {
    scale = in_segment / timing_.ramp_s;
  } else if (in_segment < timing_.ramp_s + timing_.hold_s) {
    scale = 1.0;
  }
  auto c = omni_command(static_cast<OmniDirection>(segment));
  for (double& v : c) v *= scale;
  return c;
}

void OmniEpisode::observe(hal::Tick tick, const sim::SimWorld& world) {
  const double yaw_now = torso_yaw(world.torso_pose());
  if (!started_) {
    yaw_.reset(yaw_now);
    started_ = true;
  } else {
    yaw_.update(yaw_now);
  }
  const double length = timing_.ramp_s + timing_.hold_s + timing_.stop_s;
  for (int k = 0; k < kOmniSegments; ++k) {
    const double begin = timing_.start_s + k * length + timing_.ramp_s;
    const auto begin_tick = static_cast<hal::Tick>(std::llround(begin / period_s_));
    const auto end_tick =
        static_cast<hal::Tick>(std::llround((begin + timing_.hold_s) / period_s_));
    if (tick == begin_tick) {
      hold_start_[k] = walking_frame(world.ground_truth(), yaw_.yaw());
    } else if (tick == end_tick) {
      const PlanarPose end = walking_frame(world.ground_truth(), yaw_.yaw());
      const auto c = omni_command(static_cast<OmniDirection>(k));
      OmniSegment& s = segments_[k];
      s.measured = true;
      if (is_turn(k)) {
        s.speed = c[2] * (end.yaw - hold_start_[k].yaw) / timing_.hold_s;
        s.translation_m = std::hypot(end.x - hold_start_[k].x, end.y - hold_start_[k].y);
      } else {
        const Translation t = measure_translation(hold_start_[k], end, c[0], c[1]);
        s.speed = t.along_m / timing_.hold_s;
        s.drift_ratio = t.drift_ratio();
        s.heading_change_rad = t.heading_change_rad;
      }
    }
  }
}

bool every_segment_measured(const OmniSegments& segments) {
  for (const OmniSegment& s : segments)
    if (!s.measured) return false;
  return true;
}

double omni_speed_objective(const OmniSegments& s) {
  auto v = [&](OmniDirection d) { return s[static_cast<int>(d)].speed; };
  const double sideways = 0.5 * (v(OmniDirection::kLeft) + v(OmniDirection::kRight));
  const double turning = 0.5 * (v(OmniDirection::kTurnLeft) + v(OmniDirection::kTurnRight));
  return -(v(OmniDirection::kForward) + v(OmniDirection::kBackward) + 2.0 * sideways +
           0.2 * turning);
}

namespace {

/// Each segment adds at most 1 to a constraint's violation, and a segment not reached adds 1:
/// falling earlier never lowers the violation.
double term(bool measured, double violation) {
  return measured ? std::max(-1.0, violation) : -1.0;
}

}  // namespace

double drift_term(bool measured, double drift_ratio, const StraightnessLimits& limits) {
  return term(measured, limit_violation(drift_ratio, limits.max_drift_ratio) /
                            std::max(limits.max_drift_ratio, 0.01));
}

double heading_term(bool measured, double heading_change_rad, const StraightnessLimits& limits) {
  const double heading_limit = limits.max_heading_change_deg * std::numbers::pi / 180.0;
  return term(measured, limit_violation(heading_change_rad / heading_limit, 1.0));
}

double turn_translation_term(bool measured, double translation_m,
                             const StraightnessLimits& limits) {
  return term(measured, limit_violation(translation_m / limits.max_turn_translation_m, 1.0));
}

std::array<double, 3> omni_constraints(const OmniSegments& segments,
                                       const StraightnessLimits& limits) {
  std::array<double, 3> c{0.0, 0.0, 0.0};
  for (int k = 0; k < kOmniSegments; ++k) {
    const OmniSegment& s = segments[k];
    if (is_turn(k)) {
      if (limits.max_turn_translation_m > 0.0)
        c[2] += turn_translation_term(s.measured, s.translation_m, limits);
    } else {
      if (limits.max_drift_ratio >= 0.0) c[0] += drift_term(s.measured, s.drift_ratio, limits);
      if (limits.max_heading_change_deg > 0.0)
        c[1] += heading_term(s.measured, s.heading_change_rad, limits);
    }
  }
  return c;
}

}  // namespace stride::opt
