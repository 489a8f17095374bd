// Footstep planning and velocity handling of the walk (igus.md 2.2, 2.3): the normalised
// command is scaled to the velocity limits, slowed while turning, rate-limited once per step,
// and turned into the next swing-foot destination with the step limits and the collision
// margin. Velocities are per step: m/step and rad/step.
#pragma once

#include "stride/firmware/walk/pose2.hpp"
#include "stride/firmware/walk/walk_parameters.hpp"

namespace stride::fw::walk {

/// Igus constants the planner uses (NUbots KinematicsConfiguration igus1, igus.md 2.1).
struct PlannerGeometry {
  static constexpr double kHipOffsetY = 0.055;        ///< half the hip spacing [m]
  static constexpr double kLengthBetweenLegs = 0.11;  ///< 2 * kHipOffsetY [m]
  static constexpr double kFootLength = 0.215;        ///< sole length [m]
};

/// Which foot swings (moves) in the current step.
enum class Foot : int { kLeft = 1, kRight = -1 };

inline Foot other(Foot foot) noexcept {
  return foot == Foot::kLeft ? Foot::kRight : Foot::kLeft;
}

/// Scales a normalised command (each component in [-1, 1]; NaN counts as 0) to a velocity
/// [m/step, rad/step]: positive parts by the max limit, negative parts by |min limit|, clamped
/// to the limits, then the planar part capped at vx_max * max(0, 1 - |w| / turning_factor)
/// (NUbots lets that factor go negative and reverses the walk; Stride floors it at 0).
PlanarVector scale_command(const PlanarVector& normalised, const WalkParameters& p) noexcept;

/// Moves `current` towards `target` by at most the acceleration limits times dt [s] per axis;
/// the "high" limits apply while current.x > velocity_high.
PlanarVector accelerate(const PlanarVector& current, const PlanarVector& target, double dt,
                        const WalkParameters& p) noexcept;

/// Nominal lateral foot offset (0, 0.055 - foot_offset_y, 0) from the torso / feet midpoint.
Pose2 nominal_foot_offset(const WalkParameters& p) noexcept;

/// The swing foot's destination for velocity v (m/step, rad/step): the feet midpoint moved
/// by v then v/2 (the torso's catch-up half step), plus the nominal offset on the swing side;
/// then, relative to the support foot: x clamped to [x_min, x_max], outward y to
/// [max(y_min, collision), y_max] with collision = (0.11 - limit_margin_y) + L_foot/2 * |dtheta|
/// (the collision margin wins over y_max), outward yaw to [angle_min, angle_max].
Pose2 plan_swing_destination(Foot swing, const Pose2& swing_source, const Pose2& support,
                             const PlanarVector& v, const WalkParameters& p) noexcept;

/// The last step: the swing foot lands beside the support foot at the nominal width.
Pose2 plan_closing_step(Foot swing, const Pose2& support, const WalkParameters& p) noexcept;

/// A foot's support point (the ZMP target while it supports): foot (+) (-foot_offset_x,
/// -side * foot_offset_y), i.e. |foot_offset_x| ahead and |foot_offset_y| outward of the
/// ankle for the default negative offsets (as in the NUbots code).
Pose2 support_point(Foot foot, const Pose2& pose, const WalkParameters& p) noexcept;

/// Torso destination: midpoint of the two feet's support points.
Pose2 torso_between(const Pose2& left, const Pose2& right, const WalkParameters& p) noexcept;

}  // namespace stride::fw::walk
