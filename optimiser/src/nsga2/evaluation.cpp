// sanitise(): evaluator outcomes to finite results.
#include "stride/optimiser/nsga2/evaluation.hpp"

#include <cmath>

namespace stride::opt {
namespace {

Result failed_result(const ProblemShape& shape, std::string reason) {
  Result r;
  r.objectives.assign(static_cast<std::size_t>(shape.objectives), kFailedObjective);
  r.constraints.assign(static_cast<std::size_t>(shape.constraints), -kFailedViolation);
  r.violation = kFailedViolation;
  r.failed = true;
  r.reason = std::move(reason);
  return r;
}

bool out_of_range(double v) {
  return !std::isfinite(v) || std::fabs(v) > kMaxMagnitude;
}

}  // namespace

Result sanitise(const ProblemShape& shape, EvaluationOutcome outcome) {
  if (outcome.failed) {
    return failed_result(shape, outcome.reason.empty() ? "evaluation failed" : outcome.reason);
  }
  if (outcome.objectives.size() != static_cast<std::size_t>(shape.objectives)) {
    return failed_result(shape, "evaluator returned " + std::to_string(outcome.objectives.size()) +
                                    " objectives, expected " + std::to_string(shape.objectives));
  }
  if (outcome.constraints.size() != static_cast<std::size_t>(shape.constraints)) {
    return failed_result(shape, "evaluator returned " + std::to_string(outcome.constraints.size()) +
                                    " constraints, expected " + std::to_string(shape.constraints));
  }
  for (std::size_t i = 0; i < outcome.objectives.size(); ++i) {
    if (out_of_range(outcome.objectives[i])) {
      return failed_result(shape,
                           "objective " + std::to_string(i) + " is not finite or beyond 1e30");
    }
  }
  Result r;
  r.objectives = std::move(outcome.objectives);
  r.constraints = std::move(outcome.constraints);
  for (std::size_t i = 0; i < r.constraints.size(); ++i) {
    const double g = r.constraints[i];
    if (out_of_range(g)) {
      return failed_result(shape,
                           "constraint " + std::to_string(i) + " is not finite or beyond 1e30");
    }
    if (g < 0.0) r.violation -= g;
  }
  if (r.violation > kFailedViolation) r.violation = kFailedViolation;
  return r;
}

}  // namespace stride::opt
