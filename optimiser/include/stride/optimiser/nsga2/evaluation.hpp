// Evaluation results and how NSGA-II sees them.
//
// An evaluator returns an EvaluationOutcome: the objective values (all minimised), the
// constraint values (g >= 0 is satisfied, g < 0 a violation of -g), or a failure with a reason
// (simulator failure, time-out). sanitise() turns it into a Result that sorting can use safely:
// a failure, a wrong count, a NaN/inf or a value beyond +-kMaxMagnitude becomes an infeasible
// result with violation kFailedViolation and objectives kFailedObjective, so no NaN ever reaches
// sorting or crowding.
#pragma once

#include <string>
#include <vector>

#include "stride/optimiser/nsga2/genome.hpp"

namespace stride::opt {

inline constexpr double kMaxMagnitude = 1e30;     ///< larger |values| count as failures
inline constexpr double kFailedObjective = 1e30;  ///< objectives of a failed evaluation
inline constexpr double kFailedViolation = 1e30;  ///< violation of a failed evaluation

struct EvaluationOutcome {
  std::vector<double> objectives;
  std::vector<double> constraints;
  bool failed = false;
  std::string reason;  ///< why it failed (one line)

  static EvaluationOutcome failure(std::string why) {
    EvaluationOutcome o;
    o.failed = true;
    o.reason = std::move(why);
    return o;
  }
};

/// A sanitised evaluation: finite values only.
struct Result {
  std::vector<double> objectives;
  std::vector<double> constraints;
  double violation = 0.0;  ///< sum of -g over violated constraints; 0 means feasible
  bool failed = false;
  std::string reason;

  bool feasible() const { return violation == 0.0; }
  bool operator==(const Result&) const = default;
};

/// Checks counts and values and computes the violation (see the file comment).
Result sanitise(const ProblemShape& shape, EvaluationOutcome outcome);

}  // namespace stride::opt
