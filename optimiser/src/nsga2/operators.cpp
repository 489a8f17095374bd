// SBX, polynomial mutation, binary crossover and bit-flip mutation (formulas in operators.hpp).
#include "stride/optimiser/nsga2/operators.hpp"

#include <algorithm>
#include <cmath>

namespace stride::opt {
namespace {

constexpr double kSbxEps = 1.0e-14;

/// x^e. The distribution indices are usually whole numbers, and then x^(eta + 1) is taken by
/// repeated squaring (within a few ulp of std::pow and several times faster: pow was a fifth
/// of NSGA-II's own time per generation); any other exponent goes to std::pow.
double power(double x, double e) {
  if (e != std::floor(e) || std::fabs(e) > 256.0) return std::pow(x, e);
  auto n = static_cast<unsigned>(std::fabs(e));
  double result = 1.0;
  double base = x;
  while (n != 0) {
    if ((n & 1u) != 0) result *= base;
    base *= base;
    n >>= 1u;
  }
  return e < 0.0 ? 1.0 / result : result;
}

double spread_factor(double beta, double eta_c, double u) {
  const double alpha = 2.0 - power(beta, -(eta_c + 1.0));
  if (u <= 1.0 / alpha) return std::pow(u * alpha, 1.0 / (eta_c + 1.0));
  return std::pow(1.0 / (2.0 - u * alpha), 1.0 / (eta_c + 1.0));
}

}  // namespace

std::pair<double, double> sbx_pair(double y1, double y2, double yl, double yu, double eta_c,
                                   double u) {
  if (y1 > y2) std::swap(y1, y2);
  const double span = y2 - y1;
  const double betaq1 = spread_factor(1.0 + 2.0 * (y1 - yl) / span, eta_c, u);
  const double betaq2 = spread_factor(1.0 + 2.0 * (yu - y2) / span, eta_c, u);
  double c1 = 0.5 * ((y1 + y2) - betaq1 * span);
  double c2 = 0.5 * ((y1 + y2) + betaq2 * span);
  c1 = std::clamp(c1, yl, yu);
  c2 = std::clamp(c2, yl, yu);
  return {c1, c2};
}

void sbx_crossover(const std::vector<double>& p1, const std::vector<double>& p2,
                   const std::vector<RealLimits>& limits, double cross_prob, double eta_c, Rng& rng,
                   std::vector<double>& c1, std::vector<double>& c2) {
  c1 = p1;
  c2 = p2;
  if (!rng.chance(cross_prob)) return;
  for (std::size_t i = 0; i < p1.size(); ++i) {
    if (!rng.chance(0.5)) continue;
    if (std::fabs(p1[i] - p2[i]) <= kSbxEps) continue;
    const double u = rng.uniform01();
    const auto [lo, hi] = sbx_pair(p1[i], p2[i], limits[i].min, limits[i].max, eta_c, u);
    if (rng.chance(0.5)) {
      c1[i] = hi;
      c2[i] = lo;
    } else {
      c1[i] = lo;
      c2[i] = hi;
    }
  }
}

double polynomial_mutation_value(double y, double yl, double yu, double eta_m, double u) {
  const double range = yu - yl;
  const double d1 = (y - yl) / range;
  const double d2 = (yu - y) / range;
  const double exponent = 1.0 / (eta_m + 1.0);
  double dq = 0.0;
  if (u <= 0.5) {
    const double val = 2.0 * u + (1.0 - 2.0 * u) * power(1.0 - d1, eta_m + 1.0);
    dq = std::pow(val, exponent) - 1.0;
  } else {
    const double val = 2.0 * (1.0 - u) + 2.0 * (u - 0.5) * power(1.0 - d2, eta_m + 1.0);
    dq = 1.0 - std::pow(val, exponent);
  }
  return std::clamp(y + dq * range, yl, yu);
}

int polynomial_mutation(std::vector<double>& genes, const std::vector<RealLimits>& limits,
                        double mut_prob, double eta_m, Rng& rng) {
  int changed = 0;
  for (std::size_t i = 0; i < genes.size(); ++i) {
    if (!rng.chance(mut_prob)) continue;
    genes[i] =
        polynomial_mutation_value(genes[i], limits[i].min, limits[i].max, eta_m, rng.uniform01());
    ++changed;
  }
  return changed;
}

void binary_crossover(const std::vector<std::uint8_t>& p1, const std::vector<std::uint8_t>& p2,
                      const std::vector<BinaryGene>& genes, double cross_prob, Rng& rng,
                      std::vector<std::uint8_t>& c1, std::vector<std::uint8_t>& c2) {
  c1 = p1;
  c2 = p2;
  if (genes.empty() || !rng.chance(cross_prob)) return;
  std::size_t start = 0;
  for (const BinaryGene& gene : genes) {
    const auto bits = static_cast<std::size_t>(gene.bits);
    const std::size_t site = static_cast<std::size_t>(rng.below(bits));
    for (std::size_t b = site; b < bits; ++b) std::swap(c1[start + b], c2[start + b]);
    start += bits;
  }
}

int bit_flip_mutation(std::vector<std::uint8_t>& bits, double mut_prob, Rng& rng) {
  int flipped = 0;
  for (std::uint8_t& bit : bits) {
    if (!rng.chance(mut_prob)) continue;
    bit = bit != 0 ? 0 : 1;
    ++flipped;
  }
  return flipped;
}

}  // namespace stride::opt
