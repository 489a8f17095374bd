// Problem: what the optimiser optimises. A test function or a robot task implements it.
//
// evaluate() must be a pure function of the genome (same genome, same outcome) and safe to call
// from several threads at once. A problem may also describe its known Pareto front, which the
// indicators (hypervolume, IGD) use to normalise and compare.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stride/optimiser/nsga2/evaluation.hpp"
#include "stride/optimiser/nsga2/genome.hpp"

namespace stride::opt {

/// Where the indicators measure from: ideal and nadir points of the true (or expected) front,
/// used to normalise objectives to [0, 1]; optionally a sample of the true front (for IGD) and
/// its exact hypervolume in the normalised space with reference point 1.1 per objective.
struct FrontReference {
  std::vector<double> ideal;
  std::vector<double> nadir;
  std::vector<std::vector<double>> front;  ///< sample of the true front (may be empty)
  std::optional<double> true_hypervolume;  ///< normalised, reference point 1.1
};

class Problem {
 public:
  virtual ~Problem() = default;
  virtual std::string name() const = 0;
  virtual const ProblemShape& shape() const = 0;
  /// Evaluates one genome (reals in limits; binary genes decoded with decode_binaries()).
  virtual EvaluationOutcome evaluate(const Genome& genome) const = 0;
  /// The known front, if any.
  virtual std::optional<FrontReference> reference() const { return std::nullopt; }
};

}  // namespace stride::opt
