// Evaluators: how a batch of genomes gets evaluated. The driver hands a batch to an evaluator,
// which calls `report(index, outcome)` once per candidate, in any order, always on the calling
// thread. An exception thrown by Problem::evaluate becomes a failed outcome naming it. Each
// candidate is evaluated on its own draw (Candidate::draw, Problem::evaluate_on).
//   SerialEvaluator      one after the other, in batch order;
//   ThreadPoolEvaluator  `jobs` worker threads sharing the parts of the whole batch
//                        (Problem::part_count: a robot task's episodes), taken in batch and
//                        part order; a candidate's parts are folded in part order by the
//                        worker that finishes its last one, so each outcome is the same bits
//                        for any thread count. Results are reported as they finish, so their
//                        order varies from run to run (the optimiser does not depend on it).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "stride/optimiser/nsga2/nsga2.hpp"
#include "stride/optimiser/nsga2/problem.hpp"

namespace stride::opt {

using ReportFn = std::function<void(std::size_t index, EvaluationOutcome outcome)>;

class Evaluator {
 public:
  virtual ~Evaluator() = default;
  virtual void evaluate(const Problem& problem, const std::vector<Candidate>& batch,
                        const ReportFn& report) = 0;
};

/// Problem::evaluate_on(genome, draw) with exceptions turned into failures.
EvaluationOutcome evaluate_safely(const Problem& problem, const Genome& genome,
                                  std::uint64_t draw = 0);

class SerialEvaluator final : public Evaluator {
 public:
  void evaluate(const Problem& problem, const std::vector<Candidate>& batch,
                const ReportFn& report) override;
};

class ThreadPoolEvaluator final : public Evaluator {
 public:
  explicit ThreadPoolEvaluator(int jobs) : jobs_(jobs < 1 ? 1 : jobs) {}
  void evaluate(const Problem& problem, const std::vector<Candidate>& batch,
                const ReportFn& report) override;

 private:
  int jobs_;
};

}  // namespace stride::opt
