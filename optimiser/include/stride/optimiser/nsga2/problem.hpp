// Problem: what the optimiser optimises. A test function or a robot task implements it.
//
// evaluate() must be a pure function of the genome (same genome, same outcome) and safe to call
// from several threads at once. A problem may also describe its known Pareto front, which the
// indicators (hypervolume, IGD) use to normalise and compare.
//
// Parts: an evaluation may split into independent parts (a robot task: one per episode), so
// that an evaluator can spread the parts of a whole batch over its workers and no core idles
// while one slow genome finishes. part_count(), evaluate_part() and fold_parts() must agree
// with evaluate(): folding the parts 0..n-1, in that order, gives evaluate()'s outcome bit for
// bit, whichever thread ran which part. The defaults make the whole evaluate() one part.
//
// Draws: a noisy problem (a robot task's randomised trial worlds) may be evaluated on another
// draw of its noise (Candidate::draw, Nsga2Settings::resample; draw 0 is evaluate()). The
// outcome must be a pure function of the genome and the draw. A problem without noise ignores
// the draw (the defaults do).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
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

/// The result of one part of an evaluation; each problem derives its own.
class PartResult {
 public:
  virtual ~PartResult() = default;
};

class Problem {
 public:
  virtual ~Problem() = default;
  virtual std::string name() const = 0;
  virtual const ProblemShape& shape() const = 0;
  /// Evaluates one genome (reals in limits; binary genes decoded with decode_binaries()).
  virtual EvaluationOutcome evaluate(const Genome& genome) const = 0;
  /// Evaluates one genome on draw `draw` of the problem's noise; the default ignores the draw.
  virtual EvaluationOutcome evaluate_on(const Genome& genome, std::uint64_t draw) const;
  /// The known front, if any.
  virtual std::optional<FrontReference> reference() const { return std::nullopt; }

  /// Number of independent parts of one evaluation of `genome` (>= 1).
  virtual std::size_t part_count(const Genome& genome) const;
  /// Part `part` (< part_count) of the evaluation. Thread-safe, like evaluate(); it may throw
  /// (the evaluator then fails the whole evaluation, naming the part).
  virtual std::unique_ptr<PartResult> evaluate_part(const Genome& genome, std::size_t part,
                                                    std::uint64_t draw) const;
  /// The evaluation's outcome from all of its parts, in part order.
  virtual EvaluationOutcome fold_parts(const Genome& genome,
                                       std::vector<std::unique_ptr<PartResult>>& parts) const;
};

}  // namespace stride::opt
