// MotionGuard implementation (see the header for the rules).
#include "stride/firmware/console/motion_guard.hpp"

namespace stride::fw::console {

bool MotionSituation::moving() const {
  return walk_requested || state == MotionState::kWalk || state == MotionState::kScript ||
         state == MotionState::kGetUp || state == MotionState::kFalling;
}

std::string MotionSituation::describe() const {
  switch (state) {
    case MotionState::kWalk:
      return "walking";
    case MotionState::kScript:
      return "playing a script";
    case MotionState::kGetUp:
      return "getting up";
    case MotionState::kFallen:
      return "fallen";
    case MotionState::kFalling:
      return "falling";
    case MotionState::kStand:
      break;
  }
  return walk_requested ? "walk requested" : "standing";
}

Status check_writes(const ParameterStore& params, const std::vector<ParamWrite>& batch,
                    const MotionSituation& now) {
  if (now.standing_still()) return {};
  for (const auto& [name, value] : batch) {
    if (name.rfind("safety.", 0) != 0) continue;
    double live = 0.0;
    if (params.get(name, live) && live == value) continue;  // unchanged: harmless
    return Status::error(name + " may only change while standing still (now " + now.describe() +
                         "; send stop first)");
  }
  return {};
}

Status check_torque_off(const MotionSituation& now, bool force) {
  if (force || !now.moving()) return {};
  return Status::error("torque off while " + now.describe() +
                       " would drop the robot; send stop first or use 'torque off force'");
}

Status check_walk(const MotionSituation& now) {
  if (!now.torque_on) return Status::error("walk with the torque off; send 'torque on' first");
  if (now.state == MotionState::kFallen || now.state == MotionState::kGetUp ||
      now.state == MotionState::kFalling) {
    return Status::error("walk while " + now.describe() + "; wait until the robot stands");
  }
  return {};
}

}  // namespace stride::fw::console
