// Swing-foot trajectory and hip-roll compensation ramp over one step (igus.md 2.5).
// phi in [0, 1] is the step phase; phi1, phi2 the single-support start and end.
//   psi_s = clamp((phi - phi1)/(phi2 - phi1), 0, 1)       single-support phase
//   psi   = psi_s^0.8 - 0.17 psi_s (1 - psi_s)            skewed phase
//   x_f   = (1 - cos(pi psi))/2                            horizontal fraction (0 -> 1)
//   z_f   = (1 - cos(2 pi psi))/2                          vertical fraction (0 -> 1 -> 0)
//   lift  = step_height * z_f * (slow + (fast - slow) * speed) [m],
//   speed = min(1, max(|vx|/(10 a_x), |vy|/(10 a_y))) with the acceleration limits in use.
//   k_c   = min(1, psi_s/0.1, (1 - psi_s)/0.1)             hip-roll compensation ramp
#pragma once

#include "stride/firmware/walk/walk_parameters.hpp"

namespace stride::fw::walk {

struct SwingProfile {
  double single_support_phase = 0.0;  ///< psi_s
  double horizontal = 0.0;            ///< x_f
  double vertical = 0.0;              ///< z_f
  double compensation = 0.0;          ///< k_c
};

SwingProfile swing_profile(double phase, double phi1, double phi2) noexcept;

/// Lift factor k = slow + (fast - slow) * speed for the current velocity [m/step].
double lift_factor(const PlanarVector& velocity, const WalkParameters& p) noexcept;

}  // namespace stride::fw::walk
