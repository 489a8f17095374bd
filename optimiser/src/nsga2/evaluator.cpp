// Serial and thread-pool evaluators.
#include "stride/optimiser/nsga2/evaluator.hpp"

#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>

namespace stride::opt {

EvaluationOutcome evaluate_safely(const Problem& problem, const Genome& genome) {
  try {
    return problem.evaluate(genome);
  } catch (const std::exception& e) {
    return EvaluationOutcome::failure(std::string("evaluation threw: ") + e.what());
  } catch (...) {
    return EvaluationOutcome::failure("evaluation threw an unknown exception");
  }
}

void SerialEvaluator::evaluate(const Problem& problem, const std::vector<Candidate>& batch,
                               const ReportFn& report) {
  for (std::size_t i = 0; i < batch.size(); ++i)
    report(i, evaluate_safely(problem, batch[i].genome));
}

void ThreadPoolEvaluator::evaluate(const Problem& problem, const std::vector<Candidate>& batch,
                                   const ReportFn& report) {
  std::atomic<std::size_t> next{0};
  std::mutex mutex;
  std::condition_variable ready;
  std::deque<std::pair<std::size_t, EvaluationOutcome>> done;
  auto work = [&] {
    for (;;) {
      const std::size_t i = next.fetch_add(1);
      if (i >= batch.size()) return;
      EvaluationOutcome outcome = evaluate_safely(problem, batch[i].genome);
      {
        const std::lock_guard<std::mutex> lock(mutex);
        done.emplace_back(i, std::move(outcome));
      }
      ready.notify_one();
    }
  };
  std::vector<std::thread> workers;
  const std::size_t count = std::min<std::size_t>(static_cast<std::size_t>(jobs_), batch.size());
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
