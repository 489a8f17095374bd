// WorldRng: portable normal draws (Box-Muller).
#include "stride/sim_hal/world_rng.hpp"

#include <cmath>

namespace stride::sim {

double WorldRng::normal() {
  if (have_spare_) {
    have_spare_ = false;
    return spare_;
  }
  double u1 = uniform();
  while (u1 <= 0.0) u1 = uniform();
  const double u2 = uniform();
  const double radius = std::sqrt(-2.0 * std::log(u1));
  const double angle = 2.0 * M_PI * u2;
  spare_ = radius * std::sin(angle);
  have_spare_ = true;
  return radius * std::cos(angle);
}

}  // namespace stride::sim
