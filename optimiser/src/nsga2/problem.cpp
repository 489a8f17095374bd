// Problem's default parts: the whole evaluation is one part (see problem.hpp).
#include "stride/optimiser/nsga2/problem.hpp"

#include <string>

namespace stride::opt {

namespace {

/// The one part of a problem that does not split: its whole outcome.
struct WholeEvaluation final : PartResult {
  explicit WholeEvaluation(EvaluationOutcome o) : outcome(std::move(o)) {}
  EvaluationOutcome outcome;
};

}  // namespace

std::size_t Problem::part_count(const Genome&) const {
  return 1;
}

EvaluationOutcome Problem::evaluate_on(const Genome& genome, std::uint64_t) const {
  return evaluate(genome);
}

std::unique_ptr<PartResult> Problem::evaluate_part(const Genome& genome, std::size_t,
                                                   std::uint64_t draw) const {
  return std::make_unique<WholeEvaluation>(evaluate_on(genome, draw));
}

EvaluationOutcome Problem::fold_parts(const Genome&,
                                      std::vector<std::unique_ptr<PartResult>>& parts) const {
  if (parts.size() != 1 || parts[0] == nullptr)
    return EvaluationOutcome::failure("one part expected, " + std::to_string(parts.size()) +
                                      " given");
  auto* whole = dynamic_cast<WholeEvaluation*>(parts[0].get());
  if (whole == nullptr) return EvaluationOutcome::failure("the part is not a whole evaluation");
  return std::move(whole->outcome);
}

}  // namespace stride::opt
