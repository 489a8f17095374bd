// Arm swing between the start and end poses over a step, with the shoulder-roll floor that
// keeps the arms clear of the body (igus.md 2.5). Angles in the NUbots convention (as the
// parameters); the engine converts the shoulder pitch to URDF (- pi/2).
//   e   = (1 - cos(pi phi))/2, and 1 - e while the left leg swings
//   q_L = e q_L,start + (1 - e) q_L,end,   q_R = (1 - e) q_R,start + e q_R,end
//   roll floor (outward, each side) = 5 deg + max(0, yaw_out)/2 + max(0, |y| - 0.04)/0.02 * 6 deg
//   where y [m] and yaw_out [rad] are that side's foot relative to the torso (yaw signed
//   outward). Outward is +roll for the left arm, -roll for the right.
#pragma once

#include "stride/firmware/walk/footstep_planner.hpp"
#include "stride/firmware/walk/pose2.hpp"
#include "stride/firmware/walk/walk_parameters.hpp"

namespace stride::fw::walk {

struct ArmTargets {
  ArmPose left;
  ArmPose right;
};

ArmTargets arm_swing(double phase, Foot swing, const Pose2& left_foot_in_torso,
                     const Pose2& right_foot_in_torso, const WalkParameters& p) noexcept;

}  // namespace stride::fw::walk
