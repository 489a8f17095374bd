// Optimiser speed: NSGA-II overhead per generation (pop 100, 30 genes, evaluation excluded as far
// as possible: ZDT1 costs ~0.1 us per genome), non-dominated sorting of 10,000 points in two and
// three objectives, and hypervolume of a population. Figures in tests/bench/RESULTS.md.
#include <benchmark/benchmark.h>

#include "stride/optimiser/nsga2/indicators.hpp"
#include "stride/optimiser/nsga2/nsga2.hpp"
#include "stride/optimiser/nsga2/sorting.hpp"
#include "stride/optimiser/problems/test_problems.hpp"

namespace {

using namespace stride::opt;

void BM_GenerationOverhead(benchmark::State& state) {
  const auto problem = make_test_problem("zdt1");
  Nsga2Settings s;
  s.pop_size = 100;
  s.generations = 250;  // a full run's cache size; a fresh run starts after each 250
  s.real_mut_prob = 1.0 / 30;
  std::unique_ptr<Nsga2> engine;
  std::vector<EvaluationOutcome> outcomes;
  for (auto _ : state) {
    // Evaluate outside the timed region; time ask + tell + advance (selection, variation,
    // sorting, crowding, survival, cache).
    state.PauseTiming();
    if (!engine || engine->finished()) {
      if (!Nsga2::create(s, problem->shape(), std::nullopt, engine).is_ok()) {
        state.SkipWithError("create failed");
        return;
      }
    }
    const std::vector<Candidate> batch = engine->ask();
    outcomes.clear();
    for (const Candidate& c : batch) outcomes.push_back(problem->evaluate(c.genome));
    state.ResumeTiming();
    const std::vector<Candidate> again = engine->ask();
    for (std::size_t i = 0; i < again.size(); ++i) {
      if (!engine->tell(again[i].id, outcomes[i]).is_ok()) state.SkipWithError("tell failed");
    }
    if (!engine->advance().is_ok()) state.SkipWithError("advance failed");
  }
  state.counters["ms_per_generation"] =
      benchmark::Counter(static_cast<double>(state.iterations()) / 1000.0,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_GenerationOverhead)->Unit(benchmark::kMicrosecond);

/// A whole 250-generation ZDT1 run (25,000 evaluations at ~0.1 us each, i.e. ~0.01 ms per
/// generation of evaluation) without pausing the timer, whose system calls are slow in a VM.
void BM_FullRunZdt1(benchmark::State& state) {
  const auto problem = make_test_problem("zdt1");
  Nsga2Settings s;
  s.pop_size = 100;
  s.generations = 250;
  s.real_mut_prob = 1.0 / 30;
  for (auto _ : state) {
    std::unique_ptr<Nsga2> engine;
    if (!Nsga2::create(s, problem->shape(), std::nullopt, engine).is_ok()) {
      state.SkipWithError("create failed");
      return;
    }
    while (!engine->finished()) {
      for (const Candidate& c : engine->ask()) {
        if (!engine->tell(c.id, problem->evaluate(c.genome)).is_ok()) state.SkipWithError("tell");
      }
      if (!engine->advance().is_ok()) state.SkipWithError("advance failed");
    }
    benchmark::DoNotOptimize(engine->population().data());
  }
  state.counters["ms_per_generation"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 250 / 1000.0,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_FullRunZdt1)->Unit(benchmark::kMillisecond);

Points random_points(std::size_t n, std::size_t m, std::uint64_t seed) {
  Rng rng(seed);
  Points pts(n, std::vector<double>(m));
  for (auto& p : pts) {
    for (double& v : p) v = rng.uniform01();
  }
  return pts;
}

void BM_SortTwoObjectives10000(benchmark::State& state) {
  const Points pts = random_points(10000, 2, 1);
  for (auto _ : state) benchmark::DoNotOptimize(pareto_ranks(pts));
}
BENCHMARK(BM_SortTwoObjectives10000)->Unit(benchmark::kMillisecond);

void BM_SortThreeObjectives10000(benchmark::State& state) {
  const Points pts = random_points(10000, 3, 2);
  for (auto _ : state) benchmark::DoNotOptimize(pareto_ranks(pts));
}
BENCHMARK(BM_SortThreeObjectives10000)->Unit(benchmark::kMillisecond);

void BM_DebFastNonDominatedSort2000(benchmark::State& state) {
  const Points pts = random_points(2000, 3, 3);
  for (auto _ : state) benchmark::DoNotOptimize(fast_non_dominated_sort(pts));
}
BENCHMARK(BM_DebFastNonDominatedSort2000)->Unit(benchmark::kMillisecond);

void BM_Hypervolume3d100(benchmark::State& state) {
  Points pts = random_points(100, 3, 4);
  for (auto& p : pts) {  // points on the unit sphere: all mutually non-dominated
    double r = 0;
    for (double v : p) r += v * v;
    for (double& v : p) v /= std::sqrt(r);
  }
  for (auto _ : state) benchmark::DoNotOptimize(hypervolume(pts, {1.1, 1.1, 1.1}));
}
BENCHMARK(BM_Hypervolume3d100)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
