// CommandFrame: the targets the controller sends to the servos in one control cycle.
//
// Mirrors the seed's ServoTarget (igus.md section 7.1) after the deadline has been turned into
// a moving speed, and the MX protocol 1.0 registers written by the per-tick SYNC_WRITE
// (D, I, P gain, goal position, moving speed, torque limit; igus.md section 6.4).
#pragma once

#include <array>

#include "stride/hal/types.hpp"

namespace stride::hal {

/// Target of one servo.
struct ServoCommand {
  double position_rad = 0.0;        ///< goal position, URDF joint angle [rad]
  double moving_speed_rad_s = 0.0;  ///< speed limit towards the goal [rad/s]; 0 = maximum speed
  double p_gain = 32.0;             ///< P gain register (MX 1.0 units: Kp = P/8), 0..254
  double i_gain = 0.0;              ///< I gain register, 0..254
  double d_gain = 0.0;              ///< D gain register, 0..254
  double torque_limit = 1.0;        ///< fraction of the servo's maximum torque [0, 1]
  bool torque_enable = false;       ///< false: the servo is limp
};

/// One control cycle's commands for all 20 servos, indexed by hal::servo_index(id).
struct CommandFrame {
  Tick tick = 0;  ///< the tick these commands belong to
  std::array<ServoCommand, kServoCount> servos{};
};

}  // namespace stride::hal
