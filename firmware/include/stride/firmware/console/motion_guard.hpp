// MotionGuard: the console's safety rules, the changes refused while the robot moves.
//
// "Moving" means the motion manager is walking, playing a script or getting up, or a walk was
// requested through the console and not stopped yet (the walk starts at any tick once the
// stand pose is reached, so the request counts as motion). While moving:
//   - `torque off` is refused (the robot would collapse mid-step); `torque off force` does it;
//   - any change of a safety.* parameter (set, reset, load, flash) is refused: the safety
//     limits may only change while the robot stands still (state stand, no walk requested);
//     this also holds while fallen or getting up. A file that repeats the live safety values
//     unchanged is accepted.
// Always:
//   - `walk` is refused while the torque is off, and while fallen or getting up.
#pragma once

#include <string>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/firmware/motion_manager.hpp"
#include "stride/firmware/parameter_store.hpp"

namespace stride::fw::console {

struct MotionSituation {
  MotionState state = MotionState::kStand;
  bool walk_requested = false;
  bool torque_on = true;

  /// Walking, playing a script, getting up, or a walk requested.
  bool moving() const;
  /// Standing still: state stand and no walk requested.
  bool standing_still() const { return state == MotionState::kStand && !walk_requested; }
  /// "walking", "walk requested", "playing a script", ... for messages.
  std::string describe() const;
};

/// Refuses a batch that changes a safety.* parameter unless standing still. The message names
/// the first such parameter and the reason.
Status check_writes(const ParameterStore& params, const std::vector<ParamWrite>& batch,
                    const MotionSituation& now);
/// Refuses torque off while moving unless forced.
Status check_torque_off(const MotionSituation& now, bool force);
/// Refuses a walk while the torque is off, fallen or getting up.
Status check_walk(const MotionSituation& now);

}  // namespace stride::fw::console
