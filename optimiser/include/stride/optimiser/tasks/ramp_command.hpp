// The speed the walk plans for a normalised command along one direction, and the command that
// plans a given speed (task "walk-ramp", issue 41 point 3: the ramp's levels are speeds in m/s
// and rad/s, speed_ramp.hpp). Computed from the walk's parameters by the firmware's own
// footstep planner (firmware/src/walk/footstep_planner.cpp), as the walk engine steps.
//
// The walk engine's mapping (firmware/src/walk/walk_engine.cpp, begin_step). MotionRequest::walk
// takes a command c in [-1, 1] per axis. At each step start scale_command turns it into a
// velocity per step: c * max limit for c > 0, c * |min limit| for c < 0, of
// walk.walk_cycle.velocity.limits.{x,y,angle}_{min,max} [m/step, rad/step]; the planar part is
// then capped at velocity.limits.x_max * max(0, 1 - |w| / acceleration.turning_factor). The
// swing foot lands 1.5 v beyond the feet's midpoint (v, then the torso's half step), clamped
// relative to the support foot to walk.walk_cycle.step.limits.* (x to [x_min, x_max], outward y
// to [max(y_min, 0.11 - limit_margin_y + 0.1075 |yaw|), y_max], outward yaw to
// [angle_min, angle_max]); the torso goes midway between the feet's support points, one step per
// walk_cycle.step_time T. In a steady walk with no step limit binding, that gives
//   forward, backward, sideways: speed = c L / T [m/s], L the direction's velocity limit;
//   turns: speed = (1.5 c L - angle_min / 2) / (2 T) [rad/s], 0.75 c L / T at angle_min 0:
//          the outer foot turns 1.5 w past the inner one, and the inner one only closes up to
//          it (its outward yaw is at least angle_min), so a step pair turns 1.5 w.
// The step limits cap these: forward at step.x_max / T, backward at |step.x_min| / T, a turn
// at about step.angle_max / (2 T) (a pair turns at most angle_max); sideways the inner foot
// stops at the collision margin beyond v = 2 (0.055 - foot_offset_y) - 0.11 + limit_margin_y
// (0.05 m/step at Ind_O), and the speed then grows at 3/4 of the rate, up to the outer foot's
// step.y_max.
//
// The code uses none of these closed forms: it runs the planner's functions (scale_command,
// plan_swing_destination, torso_between) from the nominal stance and takes the torso's speed
// over steps 60..100, so that every limit acts as it does in the walk. Not modelled: the
// acceleration limits (a level holds for seconds; the velocity reaches its target within a few
// steps), the feedback (heading hold, capture step) and the support exchange at touchdown,
// which ends steps early, so the robot may walk faster than planned.
#pragma once

#include <array>
#include <optional>

#include "stride/core/status.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/walk/walk_parameters.hpp"

namespace stride::opt {

/// The walk's parameters as the store holds them now (every walk.* row of the walk's table).
Status read_walk_parameters(const fw::ParameterStore& store, fw::walk::WalkParameters& out);

/// The steady speed the walk plans for `command` (in [0, 1]) times `axis` (one of
/// omni_command's directions): along the axis [m/s] for a translation, the yaw rate the axis's
/// way [rad/s] for a turn.
double planned_speed(const fw::walk::WalkParameters& walk, const std::array<double, 3>& axis,
                     double command);

/// The unit direction (x, y in the heading frame) of the translation the walk plans for the
/// normalised command (vx, vy, vtheta) with vx or vy nonzero, from the parameters the store
/// holds now: the engine walk.engine names maps the command to a velocity (the seed's walk:
/// scale_command, per step; the spline walk: command_velocity, walk.spline.*), so that a diagonal
/// command is judged against where the walk's own limits send it. A command along one axis plans
/// that axis (also when the walk's limit there is 0).
Status planned_direction(const fw::ParameterStore& store, const std::array<double, 3>& command,
                         std::array<double, 2>& out);

/// The smallest command in [0, 1] whose planned speed along `axis` is `speed` (>= 0), to 1e-12;
/// none when even the full command (1) plans less (the walk's limits cannot command it).
std::optional<double> command_for_speed(const fw::walk::WalkParameters& walk,
                                        const std::array<double, 3>& axis, double speed);

}  // namespace stride::opt
