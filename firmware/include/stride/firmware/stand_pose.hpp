// The igus stand pose (igus.md 3.4, NUbots Stand script) in URDF joint angles, and the P-gain
// conversion shared by the motion engines.
#pragma once

#include <array>
#include <cmath>

#include "stride/hal/types.hpp"

namespace stride::fw {

/// igus.md 3.4 Stand, converted to URDF angles (shoulder pitch = NUbots value - pi/2), head 0.
/// Indexed by servo index (Dynamixel ID - 1).
inline constexpr std::array<double, hal::kServoCount> kStandPoseRad = {
    0.3927,  0.3927,   // r/l shoulder pitch (NUbots 1.9635)
    -0.1239, 0.1239,   // r/l shoulder roll
    -2.4435, -2.4435,  // r/l elbow
    -0.0292, 0.0292,   // r/l hip yaw
    -0.0626, 0.0626,   // r/l hip roll
    -0.2041, -0.2071,  // r/l hip pitch
    0.2561,  0.2945,   // r/l knee
    -0.2394, -0.2624,  // r/l ankle pitch
    0.0691,  -0.0691,  // r/l ankle roll
    0.0,     0.0,      // head yaw, head pitch
};

/// Script/NUbots gain g in 0..100 to the MX P register: round(2.54 g), capped at 254.
inline double gain_to_p_register(double gain_percent) {
  const double p = std::round(gain_percent * 2.54);
  return p < 0.0 ? 0.0 : (p > 254.0 ? 254.0 : p);
}

}  // namespace stride::fw
