// The walk's planned speed along one direction, the command for a speed and the direction a
// command plans (ramp_command.hpp).
#include "stride/optimiser/tasks/ramp_command.hpp"

#include <algorithm>
#include <cmath>

#include "stride/firmware/walk/footstep_planner.hpp"
#include "stride/firmware/walk/spline_footsteps.hpp"
#include "stride/firmware/walk/spline_walk_parameters.hpp"

namespace stride::opt {
namespace {

namespace walk = fw::walk;

/// Steps planned before the speed is taken (the start's transient halves about every step: after
/// 60 it is below rounding), and the steps it is taken over (an even count: the walk repeats
/// every step pair).
constexpr int kSettleSteps = 60;
constexpr int kMeasuredSteps = 40;

}  // namespace

Status read_walk_parameters(const fw::ParameterStore& store, walk::WalkParameters& out) {
  walk::WalkParameters p;
  for (const auto& row : walk::walk_parameter_table())
    if (Status s = store.get(row.name, row.field(p)); !s) return s;
  out = p;
  return {};
}

double planned_speed(const walk::WalkParameters& p, const std::array<double, 3>& axis,
                     double command) {
  const walk::PlanarVector v =
      walk::scale_command({command * axis[0], command * axis[1], command * axis[2]}, p);
  const double half_width = walk::nominal_foot_offset(p).y;
  walk::Pose2 left{0.0, half_width, 0.0}, right{0.0, -half_width, 0.0};
  // As the walk engine: the first step swings the left foot, the right one walking right.
  walk::Foot swing = v.y < 0.0 ? walk::Foot::kRight : walk::Foot::kLeft;
  walk::Pose2 start, previous = walk::torso_between(left, right, p);
  double turned = 0.0;  // the torso's yaw over the measured steps, unwrapped
  for (int step = 1; step <= kSettleSteps + kMeasuredSteps; ++step) {
    const bool left_swings = swing == walk::Foot::kLeft;
    walk::Pose2& moving = left_swings ? left : right;
    moving = walk::plan_swing_destination(swing, moving, left_swings ? right : left, v, p);
    swing = walk::other(swing);
    const walk::Pose2 torso = walk::torso_between(left, right, p);
    if (step == kSettleSteps) start = torso;
    if (step > kSettleSteps) turned += walk::wrap_angle(torso.theta - previous.theta);
    previous = torso;
  }
  const double time = kMeasuredSteps * p.step_time;
  if (axis[2] != 0.0) return (axis[2] > 0.0 ? turned : -turned) / time;
  // Along the axis, in the frame of the torso at the first measured step.
  const walk::Pose2 moved = walk::relative(start, previous);
  return (moved.x * axis[0] + moved.y * axis[1]) / time;
}

std::optional<double> command_for_speed(const walk::WalkParameters& p,
                                        const std::array<double, 3>& axis, double speed) {
  if (!(speed > 0.0)) return 0.0;
  // A speed the full command plans to within 1e-9 (rounding) is commandable: at the full command.
  const double top = planned_speed(p, axis, 1.0);
  if (!(top >= speed - 1e-9)) return std::nullopt;
  const double target = std::min(speed, top);
  // Bisection keeps planned_speed(high) >= target (the planned speed rises with the command).
  double low = 0.0, high = 1.0;
  while (high - low > 1e-12) {
    const double middle = 0.5 * (low + high);
    (planned_speed(p, axis, middle) >= target ? high : low) = middle;
  }
  return high;
}

Status planned_direction(const fw::ParameterStore& store, const std::array<double, 3>& command,
                         std::array<double, 2>& out) {
  const double norm = std::hypot(command[0], command[1]);
  if (!(norm > 0.0)) return Status::error("planned_direction: the command does not translate");
  out = {command[0] / norm, command[1] / norm};
  if (command[0] == 0.0 || command[1] == 0.0) return {};  // along one axis
  double engine = 0.0;
  if (Status s = store.get("walk.engine", engine); !s) return s;
  double vx = 0.0, vy = 0.0;
  if (engine == 1.0) {
    walk::SplineWalkParameters p;
    for (const auto& row : walk::spline_walk_parameter_table())
      if (Status s = store.get(row.name, row.field(p)); !s) return s;
    const walk::WalkVelocity v = walk::command_velocity({command[0], command[1], command[2]}, p);
    vx = v.x;
    vy = v.y;
  } else {
    walk::WalkParameters p;
    if (Status s = read_walk_parameters(store, p); !s) return s;
    const walk::PlanarVector v = walk::scale_command({command[0], command[1], command[2]}, p);
    vx = v.x;
    vy = v.y;
  }
  const double speed = std::hypot(vx, vy);
  if (speed > 0.0) out = {vx / speed, vy / speed};
  return {};
}

}  // namespace stride::opt
