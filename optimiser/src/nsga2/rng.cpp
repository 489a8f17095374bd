// Rng implementation (see rng.hpp).
#include "stride/optimiser/nsga2/rng.hpp"

#include <sstream>

namespace stride::opt {

std::uint64_t Rng::below(std::uint64_t n) {
  if (n <= 1) return 0;
  // Reject the lowest (2^64 mod n) values so that every residue is equally likely.
  const std::uint64_t threshold = (0 - n) % n;
  for (;;) {
    const std::uint64_t x = engine_();
    if (x >= threshold) return x % n;
  }
}

std::string Rng::state() const {
  std::ostringstream out;
  out << engine_;
  return out.str();
}

Status Rng::restore(const std::string& text) {
  std::istringstream in(text);
  std::mt19937_64 engine;
  in >> engine;
  if (in.fail()) return Status::error("random-number state is malformed");
  std::string rest;
  if (in >> rest) return Status::error("random-number state has trailing text '" + rest + "'");
  engine_ = engine;
  return {};
}

}  // namespace stride::opt
