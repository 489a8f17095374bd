// Swing-foot profile and lift factor (equations in swing_foot.hpp).
#include "stride/firmware/walk/swing_foot.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stride::fw::walk {

SwingProfile swing_profile(double phase, double phi1, double phi2) noexcept {
  SwingProfile out;
  const double psi_s = std::clamp((phase - phi1) / (phi2 - phi1), 0.0, 1.0);
  const double psi = std::pow(psi_s, 0.8) - 0.17 * psi_s * (1.0 - psi_s);
  out.single_support_phase = psi_s;
  out.horizontal = 0.5 * (1.0 - std::cos(std::numbers::pi * psi));
  out.vertical = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * psi));
  out.compensation = std::min({1.0, psi_s / 0.1, (1.0 - psi_s) / 0.1});
  return out;
}

double lift_factor(const PlanarVector& velocity, const WalkParameters& p) noexcept {
  const PlanarVector& a =
      velocity.x > p.velocity_high ? p.acceleration_limits_high : p.acceleration_limits;
  const double speed = std::min(
      1.0, std::max(std::abs(velocity.x) / (10.0 * a.x), std::abs(velocity.y) / (10.0 * a.y)));
  return p.step_height_slow_fraction +
         (p.step_height_fast_fraction - p.step_height_slow_fraction) * speed;
}

}  // namespace stride::fw::walk
