// Nsga2Settings: the NSGA-II inputs of the seed's Appendix B that are not part of the problem
// (the problem's ProblemShape carries objectives, constraints, realVars/realLimits and
// binVars/binBits/binLimits), and their validation.
//
// Allowed ranges (validate() names the input and its range when a value is outside):
//   seed                  any unsigned 64-bit integer
//   pop_size (popSize)    4 .. 1,000,000 and a multiple of 4 (selection works in groups of four)
//   generations           1 .. 1,000,000 (the initial population counts as generation 1)
//   real_cross_prob       [0, 1]  (recommended 0.5-0.9)   SBX probability per pair of parents
//   real_mut_prob         [0, 1]  (recommended 1/n)       polynomial mutation per real gene
//   eta_c                 [0, 1000] (recommended 2-20)    SBX distribution index
//   eta_m                 [0, 1000] (recommended 5-50)    mutation distribution index
//   bin_cross_prob        [0, 1]  (recommended 0.5-0.9)   single-point crossover per pair
//   bin_mut_prob          [0, 1]  (recommended 1/bits)    bit-flip probability per bit
//   seed_mutation_fraction [0, 1] (default 0.2)           genes mutated around a start genome
//   resample              false/true (default false)      a new draw of the problem's noise
//                                                         every generation (see the field)
// Problem shape: objectives 1..64, constraints 0..1024, at least one gene, real limits finite
// with min < max, binary genes 1..52 bits with finite min < max.
#pragma once

#include <cstdint>

#include "stride/core/status.hpp"
#include "stride/optimiser/nsga2/genome.hpp"

namespace stride::opt {

struct Nsga2Settings {
  std::uint64_t seed = 1;
  int pop_size = 100;
  int generations = 250;
  double real_cross_prob = 0.9;
  double real_mut_prob = 0.1;
  double eta_c = 20.0;
  double eta_m = 20.0;
  double bin_cross_prob = 0.9;
  double bin_mut_prob = 0.05;
  double seed_mutation_fraction = 0.2;
  /// For a noisy problem (a robot task's randomised trial worlds): every generation is
  /// evaluated on its own draw (Candidate::draw = the generation's index, 0 for the initial
  /// population), and the parents are evaluated again on that draw beside their children, so
  /// that survival compares results of one draw and no genome lives on a lucky draw. A batch
  /// then holds 2 x pop_size genomes from the second generation on (children, then parents).
  bool resample = false;

  bool operator==(const Nsga2Settings&) const = default;
};

/// The draw no generation uses (generations stay below 10^6): a resampling run scores its
/// final front again on it before its picks are named (front-rescored.json).
inline constexpr std::uint64_t kRescoreDraw = 1'000'000;

Status validate(const Nsga2Settings& settings);
Status validate(const ProblemShape& shape);
/// Checks that a start genome fits the shape (gene counts, reals within limits, bits 0/1).
Status validate_genome(const ProblemShape& shape, const Genome& genome);

}  // namespace stride::opt
