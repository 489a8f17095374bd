// Validation of NSGA-II inputs and problem shapes.
#include "stride/optimiser/nsga2/settings.hpp"

#include <cmath>
#include <string>

namespace stride::opt {
namespace {

std::string num(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

Status check_range(const char* name, double v, double lo, double hi) {
  if (!std::isfinite(v) || v < lo || v > hi) {
    return Status::error(std::string(name) + " = " + num(v) + " is outside [" + num(lo) + ", " +
                         num(hi) + "]");
  }
  return {};
}

}  // namespace

Status validate(const Nsga2Settings& s) {
  if (s.pop_size < 4 || s.pop_size > 1000000 || s.pop_size % 4 != 0) {
    return Status::error("popSize = " + std::to_string(s.pop_size) +
                         " must be a multiple of 4 in [4, 1000000]");
  }
  if (s.generations < 1 || s.generations > 1000000) {
    return Status::error("generations = " + std::to_string(s.generations) +
                         " is outside [1, 1000000]");
  }
  if (auto st = check_range("realCrossProb", s.real_cross_prob, 0, 1); !st) return st;
  if (auto st = check_range("realMutProb", s.real_mut_prob, 0, 1); !st) return st;
  if (auto st = check_range("etaC", s.eta_c, 0, 1000); !st) return st;
  if (auto st = check_range("etaM", s.eta_m, 0, 1000); !st) return st;
  if (auto st = check_range("binCrossProb", s.bin_cross_prob, 0, 1); !st) return st;
  if (auto st = check_range("binMutProb", s.bin_mut_prob, 0, 1); !st) return st;
  if (auto st = check_range("seedMutationFraction", s.seed_mutation_fraction, 0, 1); !st) {
    return st;
  }
  return {};
}

Status validate(const ProblemShape& shape) {
  if (shape.objectives < 1 || shape.objectives > 64) {
    return Status::error("objectives = " + std::to_string(shape.objectives) +
                         " is outside [1, 64]");
  }
  if (shape.constraints < 0 || shape.constraints > 1024) {
    return Status::error("constraints = " + std::to_string(shape.constraints) +
                         " is outside [0, 1024]");
  }
  if (shape.reals.empty() && shape.binaries.empty()) {
    return Status::error("realVars + binVars = 0: the genome needs at least one gene");
  }
  for (std::size_t i = 0; i < shape.reals.size(); ++i) {
    const RealLimits& l = shape.reals[i];
    if (!std::isfinite(l.min) || !std::isfinite(l.max) || !(l.min < l.max)) {
      return Status::error("realLimits[" + std::to_string(i) + "] = [" + num(l.min) + ", " +
                           num(l.max) + "] must be finite with min < max");
    }
  }
  for (std::size_t i = 0; i < shape.binaries.size(); ++i) {
    const BinaryGene& b = shape.binaries[i];
    if (b.bits < 1 || b.bits > 52) {
      return Status::error("binBits[" + std::to_string(i) + "] = " + std::to_string(b.bits) +
                           " is outside [1, 52]");
    }
    if (!std::isfinite(b.min) || !std::isfinite(b.max) || !(b.min < b.max)) {
      return Status::error("binLimits[" + std::to_string(i) + "] = [" + num(b.min) + ", " +
                           num(b.max) + "] must be finite with min < max");
    }
  }
  return {};
}

Status validate_genome(const ProblemShape& shape, const Genome& genome) {
  if (genome.reals.size() != shape.reals.size()) {
    return Status::error("start genome has " + std::to_string(genome.reals.size()) +
                         " real genes, the problem has " + std::to_string(shape.reals.size()));
  }
  if (genome.bits.size() != static_cast<std::size_t>(shape.total_bits())) {
    return Status::error("start genome has " + std::to_string(genome.bits.size()) +
                         " bits, the problem has " + std::to_string(shape.total_bits()));
  }
  for (std::size_t i = 0; i < genome.reals.size(); ++i) {
    const double v = genome.reals[i];
    if (!std::isfinite(v) || v < shape.reals[i].min || v > shape.reals[i].max) {
      return Status::error("start genome real gene " + std::to_string(i) + " = " + num(v) +
                           " is outside [" + num(shape.reals[i].min) + ", " +
                           num(shape.reals[i].max) + "]");
    }
  }
  for (const std::uint8_t bit : genome.bits) {
    if (bit > 1) return Status::error("start genome has a bit that is not 0 or 1");
  }
  return {};
}

}  // namespace stride::opt
