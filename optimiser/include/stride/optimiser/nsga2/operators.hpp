// NSGA-II variation operators in Deb's bounded forms (as in Deb's reference NSGA-II, which the
// seed ported).
//
// SBX (simulated binary crossover), per pair with probability real_cross_prob; then each gene
// pair with |y2 - y1| > 1e-14 crosses with probability 0.5. With y1 <= y2 in [yl, yu] and one
// uniform u in [0, 1):
//   beta   = 1 + 2 (y1 - yl) / (y2 - y1)            (for c1; 1 + 2 (yu - y2)/(y2 - y1) for c2)
//   alpha  = 2 - beta^-(etaC + 1)
//   betaq  = (u alpha)^(1/(etaC+1))                 if u <= 1/alpha
//          = (1 / (2 - u alpha))^(1/(etaC+1))       otherwise
//   c1 = ((y1 + y2) - betaq (y2 - y1)) / 2,  c2 = ((y1 + y2) + betaq (y2 - y1)) / 2,
// clamped to [yl, yu]; the children then swap sides with probability 0.5. The bounded form
// truncates the spread density so that children never leave the limits.
//
// Polynomial mutation, per gene with probability real_mut_prob; d1 = (y - yl)/(yu - yl),
// d2 = (yu - y)/(yu - yl), u uniform in [0, 1):
//   u <= 0.5: dq = (2u + (1 - 2u)(1 - d1)^(etaM+1))^(1/(etaM+1)) - 1
//   u >  0.5: dq = 1 - (2(1 - u) + 2(u - 0.5)(1 - d2)^(etaM+1))^(1/(etaM+1))
//   y' = y + dq (yu - yl), clamped to [yl, yu].
//
// Binary genes: single-point crossover per binary gene (site uniform in [0, bits), the bits
// from the site on are exchanged) for a pair with probability bin_cross_prob; bit-flip
// mutation with probability bin_mut_prob per bit.
#pragma once

#include <utility>
#include <vector>

#include "stride/optimiser/nsga2/genome.hpp"
#include "stride/optimiser/nsga2/rng.hpp"

namespace stride::opt {

/// The two SBX children (c1 <= c2, before the side swap) of one gene pair for a given u.
std::pair<double, double> sbx_pair(double y1, double y2, double yl, double yu, double eta_c,
                                   double u);

/// SBX on all real genes of two parents; writes the two children.
void sbx_crossover(const std::vector<double>& p1, const std::vector<double>& p2,
                   const std::vector<RealLimits>& limits, double cross_prob, double eta_c, Rng& rng,
                   std::vector<double>& c1, std::vector<double>& c2);

/// The mutated value of one gene for a given u.
double polynomial_mutation_value(double y, double yl, double yu, double eta_m, double u);

/// Polynomial mutation of every real gene with probability mut_prob; returns genes changed.
int polynomial_mutation(std::vector<double>& genes, const std::vector<RealLimits>& limits,
                        double mut_prob, double eta_m, Rng& rng);

/// Single-point crossover of the binary genes of two parents, with probability cross_prob.
void binary_crossover(const std::vector<std::uint8_t>& p1, const std::vector<std::uint8_t>& p2,
                      const std::vector<BinaryGene>& genes, double cross_prob, Rng& rng,
                      std::vector<std::uint8_t>& c1, std::vector<std::uint8_t>& c2);

/// Flips each bit with probability mut_prob; returns the number of bits flipped.
int bit_flip_mutation(std::vector<std::uint8_t>& bits, double mut_prob, Rng& rng);

}  // namespace stride::opt
