// Helpers for firmware tests: a parameter store + servo table + controller built the way the
// firmware builds them, and sensor frames for common situations.
#pragma once

#include <array>
#include <cmath>

#include "stride/firmware/firmware.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::test {

/// A standing robot frame whose IMU reads gravity tilted by `pitch_rad` about the torso y axis
/// (positive: leaning forward, the torso x axis tilts down).
inline hal::SensorFrame tilted_frame(double pitch_rad,
                                     const std::array<double, hal::kServoCount>& pose = {}) {
  hal::SensorFrame f = hal::ScriptedRobot::standing_frame(pose);
  const double g = 9.80665;
  f.cm730.accel_mps2 = {-g * std::sin(pitch_rad), 0.0, g * std::cos(pitch_rad)};
  return f;
}

}  // namespace stride::test
