// Rng: the optimiser's single source of randomness, portable across standard libraries.
//
// std::mt19937_64 is specified bit for bit by the C++ standard, but the distributions are not,
// so the draws used by NSGA-II are derived here from the raw 64-bit output:
//   uniform01()  = (x >> 11) * 2^-53, a double in [0, 1) on a 2^-53 grid;
//   below(n)     = an unbiased integer in [0, n) by rejection of the short top range.
// The full engine state can be saved as text and restored exactly (checkpoints).
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "stride/core/status.hpp"

namespace stride::opt {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0) : engine_(seed) {}

  std::uint64_t next_u64() { return engine_(); }
  /// Uniform double in [0, 1).
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform integer in [0, n); n must be > 0.
  std::uint64_t below(std::uint64_t n);
  /// True with probability p (p <= 0 never, p >= 1 always).
  bool chance(double p) { return uniform01() < p; }

  /// The engine state as decimal words (std::mt19937_64's stream format).
  std::string state() const;
  /// Restores a state written by state(); the error names what was malformed.
  Status restore(const std::string& text);

  bool operator==(const Rng& other) const { return engine_ == other.engine_; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace stride::opt
