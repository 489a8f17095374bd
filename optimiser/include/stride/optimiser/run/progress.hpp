// Progress of an optimisation run on stderr: a bar redrawn in place on a terminal, or one
// plain log line per generation otherwise (generation, evaluations/s, ETA, best value of each
// objective among feasible members, hypervolume).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "stride/optimiser/run/optimisation_run.hpp"

namespace stride::opt {

class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool terminal);
  /// Called after each generation.
  void print(const GenerationRecord& record);
  /// Ends the bar's line (terminal only).
  void finish();
  /// The text of one progress report (no newline), for tests.
  std::string line(const GenerationRecord& record, double evals_per_s, double eta_s) const;

 private:
  bool terminal_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point first_time_;
  std::uint64_t first_evaluations_ = 0;
  int first_generation_ = -1;
};

}  // namespace stride::opt
