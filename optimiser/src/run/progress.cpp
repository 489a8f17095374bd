// ProgressPrinter: progress bar or log lines for `stride optimise`.
#include "stride/optimiser/run/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace stride::opt {

ProgressPrinter::ProgressPrinter(bool terminal)
    : terminal_(terminal), start_(std::chrono::steady_clock::now()) {}

std::string ProgressPrinter::line(const GenerationRecord& r, double evals_per_s,
                                  double eta_s) const {
  char buf[256];
  std::string text;
  if (terminal_) {
    const int width = 24;
    const int filled = r.generations > 0 ? width * r.generation / r.generations : width;
    text += "[" + std::string(static_cast<std::size_t>(filled), '#') +
            std::string(static_cast<std::size_t>(width - filled), '.') + "] ";
  }
  std::snprintf(buf, sizeof buf, "generation %d/%d evaluations %llu %.2f evals/s ETA %.0f s",
                r.generation, r.generations, static_cast<unsigned long long>(r.evaluations),
                evals_per_s, eta_s);
  text += buf;
  if (!r.best_objectives.empty()) {
    text += " best";
    for (double f : r.best_objectives) {
      std::snprintf(buf, sizeof buf, " %.4g", f);
      text += buf;
    }
  } else {
    text += " best none feasible";
  }
  if (r.hypervolume) {
    std::snprintf(buf, sizeof buf, " hypervolume %.6f", *r.hypervolume);
    text += buf;
  }
  if (r.hypervolume_ratio) {
    std::snprintf(buf, sizeof buf, " (%.2f %%)", 100.0 * *r.hypervolume_ratio);
    text += buf;
  }
  std::snprintf(buf, sizeof buf, " front %d", r.front_size);
  text += buf;
  return text;
}

void ProgressPrinter::print(const GenerationRecord& r) {
  const auto now = std::chrono::steady_clock::now();
  if (first_generation_ < 0) {
    // Rates count from this process's start; a resumed run's earlier evaluations are excluded
    // from the second report on (the first one of a resume cannot tell them apart).
    first_generation_ = r.generation - 1;
    first_evaluations_ = first_generation_ == 0 ? 0 : r.evaluations;
    first_time_ = first_generation_ == 0 ? start_ : now;
  }
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const int done = r.generation - first_generation_;
  const double per_generation = done > 0 ? elapsed / done : 0.0;
  const double eta = per_generation * std::max(0, r.generations - r.generation);
  const double window = std::chrono::duration<double>(now - first_time_).count();
  const double rate =
      window > 0 ? static_cast<double>(r.evaluations - first_evaluations_) / window : 0.0;
  const std::string text = line(r, rate, eta);
  if (terminal_) {
    std::fprintf(stderr, "\r%s\033[K", text.c_str());
    drawn_ = true;
  } else {
    std::fprintf(stderr, "%s\n", text.c_str());
  }
  std::fflush(stderr);
}

void ProgressPrinter::finish() {
  if (terminal_ && drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

}  // namespace stride::opt
