// Writes the firmware's robot description (firmware/config/robot_description.json, read by
// fw::RobotDescription) from a URDF model: per servo joint its parent joint, origin, axis and
// child link's mass and centre of mass, so the firmware gets the rigid-body model without a URDF
// parser. `stride describe` runs it; a test checks the shipped file is what it writes.
#pragma once

#include <array>
#include <string>

#include "stride/core/status.hpp"
#include "stride/firmware/servo_table.hpp"
#include "stride/sim_hal/robot_model.hpp"

namespace stride::sim {

/// The description as JSON text. `servo_joints[i]` is the URDF joint of servo i; `source`
/// names the URDF in the file's comment. Fails (naming the joint) if a servo's joint is missing
/// from the model or a servo joint's parent link is reached through a non-servo joint.
Status write_robot_description(const RobotModel& model,
                               const std::array<std::string, hal::kServoCount>& servo_joints,
                               const fw::ServoTable& servos, const std::string& source,
                               std::string& out);

}  // namespace stride::sim
