// Serial and thread-pool evaluators.
#include "stride/optimiser/nsga2/evaluator.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>

namespace stride::opt {

EvaluationOutcome evaluate_safely(const Problem& problem, const Genome& genome,
                                  std::uint64_t draw) {
  try {
    return problem.evaluate_on(genome, draw);
  } catch (const std::exception& e) {
    return EvaluationOutcome::failure(std::string("evaluation threw: ") + e.what());
  } catch (...) {
    return EvaluationOutcome::failure("evaluation threw an unknown exception");
  }
}

void SerialEvaluator::evaluate(const Problem& problem, const std::vector<Candidate>& batch,
                               const ReportFn& report) {
  for (std::size_t i = 0; i < batch.size(); ++i)
    report(i, evaluate_safely(problem, batch[i].genome, batch[i].draw));
}

namespace {

/// Part `part` of `genome`'s evaluation, or why it failed (an exception, a missing result).
std::unique_ptr<PartResult> evaluate_part_safely(const Problem& problem, const Genome& genome,
                                                 std::size_t part, std::uint64_t draw,
                                                 std::string& error) {
  try {
    std::unique_ptr<PartResult> result = problem.evaluate_part(genome, part, draw);
    if (result == nullptr) error = "part " + std::to_string(part) + " gave no result";
    return result;
  } catch (const std::exception& e) {
    error = std::string("evaluation threw: ") + e.what();
  } catch (...) {
    error = "evaluation threw an unknown exception";
  }
  return nullptr;
}

/// The outcome of one candidate from its parts: the first failed part's error, in part order,
/// or the problem's fold.
EvaluationOutcome fold_safely(const Problem& problem, const Genome& genome,
                              std::vector<std::unique_ptr<PartResult>>& parts,
                              const std::vector<std::string>& errors) {
  for (const std::string& error : errors)
    if (!error.empty()) return EvaluationOutcome::failure(error);
  try {
    return problem.fold_parts(genome, parts);
  } catch (const std::exception& e) {
    return EvaluationOutcome::failure(std::string("evaluation threw: ") + e.what());
  } catch (...) {
    return EvaluationOutcome::failure("evaluation threw an unknown exception");
  }
}

}  // namespace

void ThreadPoolEvaluator::evaluate(const Problem& problem, const std::vector<Candidate>& batch,
                                   const ReportFn& report) {
  struct Job {
    std::size_t candidate, part;
  };
  struct Parts {
    std::vector<std::unique_ptr<PartResult>> results;
    std::vector<std::string> errors;
    std::atomic<std::size_t> remaining{0};
  };
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<std::pair<std::size_t, EvaluationOutcome>> done;
  const auto finish = [&](std::size_t index, EvaluationOutcome outcome) {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      done.emplace_back(index, std::move(outcome));
    }
    ready.notify_one();
  };
  // Every part of the batch, candidate by candidate (asked here: part_count is cheap).
  std::vector<Parts> parts(batch.size());
  std::vector<Job> jobs;
  for (std::size_t i = 0; i < batch.size(); ++i) {
    std::size_t count = 0;
    std::string error;
    try {
      count = problem.part_count(batch[i].genome);
      if (count == 0) error = "the evaluation has no parts";
    } catch (const std::exception& e) {
      error = std::string("evaluation threw: ") + e.what();
    } catch (...) {
      error = "evaluation threw an unknown exception";
    }
    if (!error.empty()) {
      finish(i, EvaluationOutcome::failure(error));
      continue;
    }
    parts[i].results.resize(count);
    parts[i].errors.resize(count);
    parts[i].remaining.store(count);
    for (std::size_t k = 0; k < count; ++k) jobs.push_back({i, k});
  }
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (;;) {
      const std::size_t j = next.fetch_add(1);
      if (j >= jobs.size()) return;
      const Job job = jobs[j];
      Parts& p = parts[job.candidate];
      const Genome& genome = batch[job.candidate].genome;
      p.results[job.part] = evaluate_part_safely(problem, genome, job.part,
                                                 batch[job.candidate].draw, p.errors[job.part]);
      // acq_rel: the worker that takes the count to zero sees every other part's writes.
      if (p.remaining.fetch_sub(1, std::memory_order_acq_rel) == 1)
        finish(job.candidate, fold_safely(problem, genome, p.results, p.errors));
    }
  };
  std::vector<std::thread> workers;
  const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(jobs_), jobs.size());
  workers.reserve(count);
  for (std::size_t t = 0; t < count; ++t) workers.emplace_back(work);
  for (std::size_t reported = 0; reported < batch.size(); ++reported) {
    std::unique_lock<std::mutex> lock(mutex);
    ready.wait(lock, [&] { return !done.empty(); });
    auto [index, outcome] = std::move(done.front());
    done.pop_front();
    lock.unlock();
    report(index, std::move(outcome));
  }
  for (std::thread& w : workers) w.join();
}

}  // namespace stride::opt
