// Spline-walk velocities and footsteps (rules and sources in spline_footsteps.hpp).
#include "stride/firmware/walk/spline_footsteps.hpp"

#include <algorithm>
#include <cmath>

namespace stride::fw::walk {
namespace {

double finite_or_zero(double v) {
  return std::isfinite(v) ? std::clamp(v, -1.0, 1.0) : 0.0;
}

double approach(double current, double target, double max_change) {
  return current + std::clamp(target - current, -max_change, max_change);
}

double sign(double v) {
  return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0);
}

}  // namespace

WalkVelocity command_velocity(const PlanarVector& command, const SplineWalkParameters& p) noexcept {
  double cx = finite_or_zero(command.x), cy = finite_or_zero(command.y);
  double cw = finite_or_zero(command.angle);
  const double norm = std::sqrt(cx * cx + cy * cy + cw * cw);
  if (norm > 1.0) {
    cx /= norm;
    cy /= norm;
    cw /= norm;
  }
  const double f = p.frequency;
  const double step_x = cx >= 0.0 ? p.max_step_forward : p.max_step_backward;
  return {cx * step_x * 2.0 * f, cy * p.max_step_side * f, cw * p.max_turn * f};
}

WalkVelocity accelerate(const WalkVelocity& current, const WalkVelocity& target, double dt,
                        const SplineWalkParameters& p) noexcept {
  return {approach(current.x, target.x, p.acceleration_x * dt),
          approach(current.y, target.y, p.acceleration_y * dt),
          approach(current.turn, target.turn, p.acceleration_turn * dt)};
}

double min_foot_distance(double toe_in, const SplineWalkParameters& p) noexcept {
  const double inward = toe_in > 0.0 ? SoleGeometry::kToe * std::sin(std::min(toe_in, 1.5)) : 0.0;
  return 2.0 * SoleGeometry::kInnerEdge + p.foot_clearance + inward;
}

Pose2 plan_spline_step(Foot swing, const Pose2& support, const WalkVelocity& v, double step_time,
                       double extra_turn, const PlanarVector& offset,
                       const SplineWalkParameters& p) noexcept {
  const double side = swing == Foot::kLeft ? 1.0 : -1.0;
  // Turn: rho = left yaw - right yaw after this step (> 0 toed out).
  const double cycle_turn = 2.0 * (v.turn * step_time + extra_turn);
  const bool opening_turn = sign(cycle_turn) == side;
  const double rho = opening_turn ? (1.0 - p.turn_inner_ratio) * std::abs(cycle_turn)
                                  : -p.turn_inner_ratio * std::abs(cycle_turn);
  const double yaw_change = side * rho;  // target yaw - support yaw
  // Sideways: the outer foot steps out by a cycle's side travel, the inner one closes up.
  const double cycle_side = 2.0 * v.y * step_time;
  const bool opening_side = sign(cycle_side) == side;
  double lateral = side * p.foot_distance + (opening_side ? cycle_side : 0.0) + offset.y;
  double forward = v.x * step_time + offset.x;
  // The collision rule, in the support foot's frame turned halfway to the target.
  const double least = std::max(min_foot_distance(-rho, p), 0.0);
  if (side * lateral < least) lateral = side * least;
  const double heading = support.theta + 0.5 * yaw_change;
  const double c = std::cos(heading), s = std::sin(heading);
  return {support.x + c * forward - s * lateral, support.y + s * forward + c * lateral,
          wrap_angle(support.theta + yaw_change)};
}

Pose2 plan_spline_closing_step(Foot swing, const Pose2& support,
                               const SplineWalkParameters& p) noexcept {
  const double side = swing == Foot::kLeft ? 1.0 : -1.0;
  const double lateral = side * std::max(p.foot_distance, min_foot_distance(0.0, p));
  return compose(support, {0.0, lateral, 0.0});
}

}  // namespace stride::fw::walk
