// WorldRng: the one seeded random generator of a simulated world.
//
// std::mt19937_64 produces the same 64-bit stream on every platform; the conversions to
// uniform and normal doubles are written here (not std::*_distribution, whose output is
// implementation-defined) so that a seed gives the same draws with any standard library.
#pragma once

#include <cstdint>
#include <random>

namespace stride::sim {

class WorldRng {
 public:
  explicit WorldRng(std::uint64_t seed = 1) : engine_(seed) {}
  void reseed(std::uint64_t seed) {
    engine_.seed(seed);
    have_spare_ = false;
  }
  std::uint64_t next_u64() { return engine_(); }
  /// Uniform in [0, 1): the top 53 bits of one draw.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Standard normal (Box-Muller, the second value of each pair kept for the next call).
  double normal();
  /// Bernoulli draw with probability p.
  bool chance(double p) { return uniform() < p; }

 private:
  std::mt19937_64 engine_;
  bool have_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace stride::sim
