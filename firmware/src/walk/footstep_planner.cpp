// Footstep planner and velocity handling (contract in footstep_planner.hpp).
#include "stride/firmware/walk/footstep_planner.hpp"

#include <algorithm>
#include <cmath>

namespace stride::fw::walk {
namespace {

double scale_axis(double command, double min_limit, double max_limit) {
  if (!std::isfinite(command)) return 0.0;
  command = std::clamp(command, -1.0, 1.0);
  const double v = command > 0.0 ? command * max_limit : command * std::abs(min_limit);
  return std::clamp(v, std::min(min_limit, 0.0), std::max(max_limit, 0.0));
}

double step_toward(double current, double target, double max_change) {
  return current + std::clamp(target - current, -max_change, max_change);
}

/// Clamp that gives `lower` priority if the bounds cross.
double clamp_lower_first(double v, double lower, double upper) {
  return std::max(std::min(v, upper), lower);
}

}  // namespace

PlanarVector scale_command(const PlanarVector& normalised, const WalkParameters& p) noexcept {
  const auto& lim = p.velocity_limits;
  PlanarVector v{scale_axis(normalised.x, lim.x_min, lim.x_max),
                 scale_axis(normalised.y, lim.y_min, lim.y_max),
                 scale_axis(normalised.angle, lim.angle_min, lim.angle_max)};
  const double factor =
      std::clamp(1.0 - std::abs(v.angle) / p.acceleration_turning_factor, 0.0, 1.0);
  const double magnitude = std::hypot(v.x, v.y);
  if (magnitude > 0.0) {
    const double capped = std::min(lim.x_max * factor, magnitude);
    v.x *= capped / magnitude;
    v.y *= capped / magnitude;
  }
  return v;
}

PlanarVector accelerate(const PlanarVector& current, const PlanarVector& target, double dt,
                        const WalkParameters& p) noexcept {
  const PlanarVector& a =
      current.x > p.velocity_high ? p.acceleration_limits_high : p.acceleration_limits;
  return {step_toward(current.x, target.x, a.x * dt), step_toward(current.y, target.y, a.y * dt),
          step_toward(current.angle, target.angle, a.angle * dt)};
}

Pose2 nominal_foot_offset(const WalkParameters& p) noexcept {
  return {0.0, PlannerGeometry::kHipOffsetY - p.foot_offset_y, 0.0};
}

Pose2 plan_swing_destination(Foot swing, const Pose2& swing_source, const Pose2& support,
                             const PlanarVector& v, const WalkParameters& p) noexcept {
  const double side = static_cast<int>(swing);
  const Pose2 middle = interpolate(swing_source, support, 0.5);
  const Pose2 velocity{v.x, v.y, v.angle};
  const Pose2 half_velocity{0.5 * v.x, 0.5 * v.y, 0.5 * v.angle};
  const Pose2 moved = compose(compose(middle, velocity), half_velocity);
  const Pose2 offset = nominal_foot_offset(p);
  const Pose2 predicted = compose(moved, {0.0, side * offset.y, 0.0});
  // Relative to the support foot, with y and theta signed outward for the swing side.
  Pose2 rel = relative(support, predicted);
  const auto& lim = p.step_limits;
  double outward_y = side * rel.y;
  double outward_theta = side * rel.theta;
  outward_theta = std::clamp(outward_theta, lim.angle_min, lim.angle_max);
  const double stance_limit_y2 = PlannerGeometry::kLengthBetweenLegs - p.limit_margin_y;
  const double collision =
      stance_limit_y2 + 0.5 * PlannerGeometry::kFootLength * std::abs(outward_theta);
  outward_y = clamp_lower_first(outward_y, std::max(lim.y_min, collision), lim.y_max);
  rel.x = std::clamp(rel.x, lim.x_min, lim.x_max);
  rel.y = side * outward_y;
  rel.theta = side * outward_theta;
  return compose(support, rel);
}

Pose2 plan_closing_step(Foot swing, const Pose2& support, const WalkParameters& p) noexcept {
  const double side = static_cast<int>(swing);
  return compose(support, {0.0, side * 2.0 * nominal_foot_offset(p).y, 0.0});
}

Pose2 support_point(Foot foot, const Pose2& pose, const WalkParameters& p) noexcept {
  const double side = static_cast<int>(foot);
  return compose(pose, {-p.foot_offset_x, -side * p.foot_offset_y, 0.0});
}

Pose2 torso_between(const Pose2& left, const Pose2& right, const WalkParameters& p) noexcept {
  return interpolate(support_point(Foot::kLeft, left, p), support_point(Foot::kRight, right, p),
                     0.5);
}

}  // namespace stride::fw::walk
