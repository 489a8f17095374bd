// Spline-walk footsteps: from the normalised command to a walking velocity, and from the
// velocity to where the swing foot lands (../shared/research/spline-walk.md, "step target from
// the command"; walk-mechanisms.md 1.1 and 1.3 for the outer-foot side step and the turn on both
// feet). Pure functions of their arguments; real-time (no allocation).
//
// Velocity: the command c in [-1, 1]^3 (NaN counts as 0) is scaled to the walk's limits,
//   vx = c_x * max_step_forward * 2f (or max_step_backward for c_x < 0),
//   vy = c_y * max_step_side * f,  w = c_w * max_turn * f            [m/s, m/s, rad/s]
// after scaling c onto the unit ball if |c| > 1 (the combined limit: full speed forward and full
// speed sideways are not both reached at once). The velocity approaches its target at the
// acceleration limits (per axis, m/s^2 and rad/s^2).
//
// Footstep (step time T = 1/(2f), swing side s = +1 left, -1 right, support foot S):
//   - forward: the swing foot lands vx T ahead of the support foot;
//   - sideways: one side step per cycle, on the outer foot: when the swing foot is on the side
//     of the motion it lands 2 vy T further out; the other step returns to the stance width;
//   - turn: a cycle turns by W = 2 w T, split between the feet. With r = turn_inner_ratio, the
//     opening step (swing foot on the side of the turn) leaves the feet toed out by (1 - r)|W|,
//     the closing step toed in by r|W|, so each step turns its foot by |W| (r = 0.5: Bit-Bots'
//     quintic walk; r = 0: the seed's toe-out-only turn);
//   - the collision rule: the ankles stay at least 0.11 m + foot_clearance apart sideways (the
//     soles' inner edges are 0.055 m inside the ankle, igus.md 1.3), plus 0.1315 sin(toe-in)
//     while toed in (the inner toe corner, 0.1315 m ahead of the ankle, swings inward);
//   - a balance offset (the capture step's, walk frame) moves the target, within the rule.
// The step's frame is the support foot turned halfway to the target's yaw.
#pragma once

#include "stride/firmware/walk/footstep_planner.hpp"
#include "stride/firmware/walk/pose2.hpp"
#include "stride/firmware/walk/spline_walk_parameters.hpp"

namespace stride::fw::walk {

/// A walking velocity: forward and left [m/s], turn [rad/s].
struct WalkVelocity {
  double x = 0.0;
  double y = 0.0;
  double turn = 0.0;
};

/// Igus sole figures the collision rule uses (igus.md 1.3, left foot frame).
struct SoleGeometry {
  static constexpr double kInnerEdge = 0.055;  ///< sole's inner edge inside the ankle [m]
  static constexpr double kToe = 0.1315;       ///< toe ahead of the ankle [m]
};

/// The velocity a normalised command asks for.
WalkVelocity command_velocity(const PlanarVector& command, const SplineWalkParameters& p) noexcept;

/// `current` moved towards `target` by at most the acceleration limits over `dt` [s].
WalkVelocity accelerate(const WalkVelocity& current, const WalkVelocity& target, double dt,
                        const SplineWalkParameters& p) noexcept;

/// Least lateral distance of the ankles [m] with the feet toed in by `toe_in` [rad] (<= 0: none).
double min_foot_distance(double toe_in, const SplineWalkParameters& p) noexcept;

/// Where the `swing` foot lands for one step of `step_time` [s] at velocity `v`, with
/// `extra_turn` [rad] added to the step's turn (the heading hold) and `offset` [m] (walk
/// frame x forward, y left) added to its position (the capture step).
Pose2 plan_spline_step(Foot swing, const Pose2& support, const WalkVelocity& v, double step_time,
                       double extra_turn, const PlanarVector& offset,
                       const SplineWalkParameters& p) noexcept;

/// The last step of a stop: beside the support foot at the stance width, parallel to it.
Pose2 plan_spline_closing_step(Foot swing, const Pose2& support,
                               const SplineWalkParameters& p) noexcept;

}  // namespace stride::fw::walk
