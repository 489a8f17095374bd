// The NSGA-II engine: validation, ask/tell in any order, determinism, cache, failures,
// seeding, checkpoint/restore, limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <mutex>
#include <set>

#include "stride/optimiser/nsga2/nsga2.hpp"
#include "stride/optimiser/nsga2/sorting.hpp"
#include "stride/optimiser/problems/test_problems.hpp"

namespace stride::opt {
namespace {

Nsga2Settings small_settings(std::uint64_t seed = 5) {
  Nsga2Settings s;
  s.seed = seed;
  s.pop_size = 20;
  s.generations = 12;
  s.real_mut_prob = 1.0 / 30;
  return s;
}

enum class Order { kForward, kReverse, kShuffled };

/// Runs an engine to the end, telling results in the given order; returns the final checkpoint.
nlohmann::json run_to_end(const Problem& problem, Nsga2& engine, Order order,
                          int stop_after_generations = -1) {
  Rng shuffle(99);
  while (!engine.finished()) {
    if (stop_after_generations >= 0 && engine.completed_generations() >= stop_after_generations) {
      break;
    }
    std::vector<Candidate> batch = engine.ask();
    if (order == Order::kReverse) std::reverse(batch.begin(), batch.end());
    if (order == Order::kShuffled) {
      for (std::size_t i = batch.size(); i > 1; --i) {
        std::swap(batch[i - 1], batch[shuffle.below(i)]);
      }
    }
    for (const Candidate& c : batch) {
      EXPECT_TRUE(engine.tell(c.id, problem.evaluate(c.genome)).is_ok());
    }
    EXPECT_TRUE(engine.advance().is_ok());
  }
  return engine.checkpoint();
}

TEST(Nsga2, ValidatesEveryInputNamingIt) {
  const ProblemShape shape = make_test_problem("zdt1")->shape();
  std::unique_ptr<Nsga2> engine;
  auto expect_error = [&](Nsga2Settings s, const std::string& word) {
    const Status st = Nsga2::create(s, shape, std::nullopt, engine);
    ASSERT_FALSE(st.is_ok()) << word;
    EXPECT_NE(st.message().find(word), std::string::npos) << st.message();
  };
  Nsga2Settings s = small_settings();
  s.pop_size = 22;
  expect_error(s, "multiple of 4");
  s = small_settings();
  s.pop_size = 0;
  expect_error(s, "popSize");
  s = small_settings();
  s.generations = 0;
  expect_error(s, "generations");
  s = small_settings();
  s.real_cross_prob = 1.5;
  expect_error(s, "realCrossProb = 1.5 is outside [0, 1]");
  s = small_settings();
  s.real_mut_prob = -0.1;
  expect_error(s, "realMutProb");
  s = small_settings();
  s.eta_c = -1;
  expect_error(s, "etaC");
  s = small_settings();
  s.eta_m = NAN;
  expect_error(s, "etaM");
  s = small_settings();
  s.bin_cross_prob = 2;
  expect_error(s, "binCrossProb");
  s = small_settings();
  s.bin_mut_prob = 7;
  expect_error(s, "binMutProb");
  s = small_settings();
  s.seed_mutation_fraction = 1.2;
  expect_error(s, "seedMutationFraction");

  auto expect_shape_error = [&](ProblemShape bad, const std::string& word) {
    const Status st = Nsga2::create(small_settings(), bad, std::nullopt, engine);
    ASSERT_FALSE(st.is_ok()) << word;
    EXPECT_NE(st.message().find(word), std::string::npos) << st.message();
  };
  ProblemShape bad = shape;
  bad.objectives = 0;
  expect_shape_error(bad, "objectives");
  bad = shape;
  bad.constraints = -1;
  expect_shape_error(bad, "constraints");
  bad = shape;
  bad.reals[3] = RealLimits{1, 1};
  expect_shape_error(bad, "realLimits[3]");
  bad = shape;
  bad.binaries = {{0, 0, 1}};
  expect_shape_error(bad, "binBits[0]");
  bad = shape;
  bad.binaries = {{4, 2, 1}};
  expect_shape_error(bad, "binLimits[0]");
  bad = ProblemShape{};
  expect_shape_error(bad, "at least one gene");

  Genome start;
  start.reals.assign(30, 0.5);
  start.reals[7] = 1.5;
  const Status st = Nsga2::create(small_settings(), shape, start, engine);
  ASSERT_FALSE(st.is_ok());
  EXPECT_NE(st.message().find("real gene 7"), std::string::npos) << st.message();
}

TEST(Nsga2, SameSeedSameRunWhateverTheOrderOfResults) {
  const auto problem = make_test_problem("zdt2");
  std::unique_ptr<Nsga2> a;
  std::unique_ptr<Nsga2> b;
  std::unique_ptr<Nsga2> c;
  ASSERT_TRUE(Nsga2::create(small_settings(), problem->shape(), std::nullopt, a).is_ok());
  ASSERT_TRUE(Nsga2::create(small_settings(), problem->shape(), std::nullopt, b).is_ok());
  ASSERT_TRUE(Nsga2::create(small_settings(), problem->shape(), std::nullopt, c).is_ok());
  const nlohmann::json forward = run_to_end(*problem, *a, Order::kForward);
  EXPECT_EQ(run_to_end(*problem, *b, Order::kReverse), forward);
  EXPECT_EQ(run_to_end(*problem, *c, Order::kShuffled), forward);
  EXPECT_EQ(a->completed_generations(), 12);
  std::unique_ptr<Nsga2> other;
  ASSERT_TRUE(Nsga2::create(small_settings(6), problem->shape(), std::nullopt, other).is_ok());
  EXPECT_NE(run_to_end(*problem, *other, Order::kForward)["population"], forward["population"]);
}

TEST(Nsga2, AskTellProtocolErrors) {
  const auto problem = make_test_problem("zdt1");
  std::unique_ptr<Nsga2> engine;
  ASSERT_TRUE(Nsga2::create(small_settings(), problem->shape(), std::nullopt, engine).is_ok());
  const std::vector<Candidate> batch = engine->ask();
  ASSERT_EQ(batch.size(), 20u);
  EXPECT_FALSE(engine->advance().is_ok());  // results missing
  EXPECT_FALSE(engine->tell(12345, problem->evaluate(batch[0].genome)).is_ok());
  ASSERT_TRUE(engine->tell(batch[0].id, problem->evaluate(batch[0].genome)).is_ok());
  EXPECT_FALSE(engine->tell(batch[0].id, problem->evaluate(batch[0].genome)).is_ok());
  EXPECT_EQ(engine->ask().size(), 19u);  // the told one is no longer handed out
  EXPECT_EQ(engine->ask().front().id, batch[1].id);
}

/// A problem on 3-bit binary genes (few distinct genomes) that records every evaluation.
class CountingBinaryProblem final : public Problem {
 public:
  CountingBinaryProblem() {
    shape_.binaries = {{3, 0, 1}, {3, 0, 1}};
    shape_.objectives = 2;
  }
  std::string name() const override { return "counting"; }
  const ProblemShape& shape() const override { return shape_; }
  EvaluationOutcome evaluate(const Genome& g) const override {
    const std::lock_guard<std::mutex> lock(mutex_);
    seen.push_back(genome_key(g));
    const std::vector<double> v = decode_binaries(shape_, g);
    EvaluationOutcome o;
    o.objectives = {v[0] + v[1], (1 - v[0]) + v[1] * v[1]};
    return o;
  }
  mutable std::vector<std::string> seen;

 private:
  ProblemShape shape_;
  mutable std::mutex mutex_;
};

TEST(Nsga2, NeverEvaluatesAGenomeTwice) {
  CountingBinaryProblem problem;
  Nsga2Settings s = small_settings();
  s.bin_mut_prob = 0.1;
  std::unique_ptr<Nsga2> engine;
  ASSERT_TRUE(Nsga2::create(s, problem.shape(), std::nullopt, engine).is_ok());
  run_to_end(problem, *engine, Order::kShuffled);
  const std::set<std::string> distinct(problem.seen.begin(), problem.seen.end());
  EXPECT_EQ(distinct.size(), problem.seen.size());  // no genome evaluated twice
  EXPECT_LE(problem.seen.size(), 64u);              // only 64 distinct genomes exist
  EXPECT_EQ(engine->counters().evaluations, problem.seen.size());
  // every batch member was either evaluated or served from the cache
  EXPECT_EQ(engine->counters().evaluations + engine->counters().cache_hits, 20u * 12u);
  EXPECT_GT(engine->counters().cache_hits, 100u);
  for (const Individual& ind : engine->population()) {
    const std::vector<double> v = decode_binaries(problem.shape(), ind.genome);
    for (const double x : v) {
      EXPECT_GE(x, 0.0);
      EXPECT_LE(x, 1.0);
    }
  }
}

/// ZDT1 whose evaluations fail in several ways when x2 falls in certain bands.
class FailingProblem final : public Problem {
 public:
  std::string name() const override { return "failing"; }
  const ProblemShape& shape() const override { return inner_->shape(); }
  EvaluationOutcome evaluate(const Genome& g) const override {
    const double x = g.reals[1];
    if (x < 0.1) return EvaluationOutcome::failure("simulated time-out");
    EvaluationOutcome o = inner_->evaluate(g);
    if (x < 0.2)
      o.objectives[0] = NAN;
    else if (x < 0.3)
      o.objectives[1] = INFINITY;
    else if (x < 0.35)
      o.objectives.pop_back();
    else if (x < 0.4)
      o.objectives[0] = 1e300;
    return o;
  }

 private:
  std::unique_ptr<Problem> inner_ = make_test_problem("zdt1");
};

TEST(Nsga2, FailedEvaluationsBecomeInfeasibleAndNoNanReachesSorting) {
  FailingProblem problem;
  Nsga2Settings s = small_settings();
  s.pop_size = 40;
  std::unique_ptr<Nsga2> engine;
  ASSERT_TRUE(Nsga2::create(s, problem.shape(), std::nullopt, engine).is_ok());
  const std::vector<Candidate> first = engine->ask();
  for (const Candidate& c : first)
    ASSERT_TRUE(engine->tell(c.id, problem.evaluate(c.genome)).is_ok());
  int failed = 0;
  for (const Individual& ind : engine->batch()) {
    for (const double f : ind.result.objectives) ASSERT_TRUE(std::isfinite(f));
    if (ind.genome.reals[1] < 0.4) {
      ++failed;
      EXPECT_TRUE(ind.result.failed);
      EXPECT_FALSE(ind.result.feasible());
      EXPECT_EQ(ind.result.violation, kFailedViolation);
      EXPECT_FALSE(ind.result.reason.empty());
    } else {
      EXPECT_TRUE(ind.result.feasible());
    }
  }
  EXPECT_GT(failed, 5);
  ASSERT_TRUE(engine->advance().is_ok());
  run_to_end(problem, *engine, Order::kForward);
  EXPECT_GT(engine->counters().failures, 0u);
  for (const Individual& ind : engine->population()) {
    EXPECT_FALSE(ind.result.failed);  // failures lose to every feasible genome
    EXPECT_FALSE(std::isnan(ind.crowding));
  }
}

TEST(Nsga2, SeedingKeepsTheStartGenomeAndMutatesAFractionOfTheOthers) {
  const auto problem = make_test_problem("zdt1");
  Genome start;
  start.reals.assign(30, 0.5);
  Nsga2Settings s = small_settings();
  s.pop_size = 200;
  std::unique_ptr<Nsga2> engine;
  ASSERT_TRUE(Nsga2::create(s, problem->shape(), start, engine).is_ok());
  // batch(), not ask(): a mutated copy identical to another member is not handed out twice.
  const std::vector<Individual>& batch = engine->batch();
  ASSERT_EQ(batch.size(), 200u);
  EXPECT_EQ(batch[0].genome, start);
  int changed = 0;
  for (std::size_t i = 1; i < batch.size(); ++i) {
    for (std::size_t k = 0; k < 30; ++k) {
      const double v = batch[i].genome.reals[k];
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, 1.0);
      if (v != 0.5) ++changed;
    }
  }
  EXPECT_NEAR(changed / (199.0 * 30.0), 0.2, 0.02);
  s.seed_mutation_fraction = 0.5;
  ASSERT_TRUE(Nsga2::create(s, problem->shape(), start, engine).is_ok());
  changed = 0;
  for (const Individual& c : engine->batch()) {
    for (const double v : c.genome.reals) changed += v != 0.5;
  }
  EXPECT_NEAR(changed / (199.0 * 30.0), 0.5, 0.03);
}

TEST(Nsga2, RestoreFromACheckpointReproducesTheUninterruptedRun) {
  const auto problem = make_test_problem("zdt3");
  std::unique_ptr<Nsga2> full;
  ASSERT_TRUE(Nsga2::create(small_settings(8), problem->shape(), std::nullopt, full).is_ok());
  const nlohmann::json expected = run_to_end(*problem, *full, Order::kForward);

  for (const int stop : {0, 1, 5}) {
    std::unique_ptr<Nsga2> first;
    ASSERT_TRUE(Nsga2::create(small_settings(8), problem->shape(), std::nullopt, first).is_ok());
    // Record every evaluation, as evaluations.jsonl does.
    std::vector<std::pair<Genome, Result>> known;
    while (first->completed_generations() < stop) {
      for (const Candidate& c : first->ask()) {
        ASSERT_TRUE(first->tell(c.id, problem->evaluate(c.genome)).is_ok());
        known.emplace_back(c.genome, first->batch_member(c.id)->result);
      }
      ASSERT_TRUE(first->advance().is_ok());
    }
    // Through text, as on disk; then some work of the next generation is lost.
    const nlohmann::json cp = nlohmann::json::parse(first->checkpoint().dump());
    const std::vector<Candidate> partial = first->ask();
    ASSERT_TRUE(first->tell(partial[0].id, problem->evaluate(partial[0].genome)).is_ok());

    std::unique_ptr<Nsga2> resumed;
    ASSERT_TRUE(Nsga2::restore(cp, problem->shape(), known, resumed).is_ok());
    EXPECT_EQ(resumed->completed_generations(), stop);
    EXPECT_EQ(run_to_end(*problem, *resumed, Order::kReverse), expected) << "stop " << stop;
  }
}

TEST(Nsga2, RestoreRejectsDamagedCheckpoints) {
  const auto problem = make_test_problem("zdt1");
  std::unique_ptr<Nsga2> engine;
  ASSERT_TRUE(Nsga2::create(small_settings(), problem->shape(), std::nullopt, engine).is_ok());
  run_to_end(*problem, *engine, Order::kForward, 2);
  const nlohmann::json good = engine->checkpoint();
  std::unique_ptr<Nsga2> out;
  nlohmann::json bad = good;
  bad["rng"] = "1 2 3";
  EXPECT_FALSE(Nsga2::restore(bad, problem->shape(), {}, out).is_ok());
  bad = good;
  bad["population"][3]["objectives"][0] = "zz";
  EXPECT_FALSE(Nsga2::restore(bad, problem->shape(), {}, out).is_ok());
  bad = good;
  bad["settings"]["pop_size"] = 21;
  EXPECT_FALSE(Nsga2::restore(bad, problem->shape(), {}, out).is_ok());
  bad = good;
  bad["batch"].erase(0);
  EXPECT_FALSE(Nsga2::restore(bad, problem->shape(), {}, out).is_ok());
  EXPECT_FALSE(Nsga2::restore(good, make_test_problem("zdt4")->shape(), {}, out).is_ok());
  EXPECT_TRUE(Nsga2::restore(good, problem->shape(), {}, out).is_ok());
}

TEST(Nsga2, ExactDoublesRoundTrip) {
  for (const double v : {0.1, -0.0, 1e-310, 1.0 / 3.0, 6.02214076e23, double{INFINITY}}) {
    double back = 0;
    ASSERT_TRUE(parse_exact_double(exact_double(v), back));
    EXPECT_EQ(std::memcmp(&back, &v, sizeof v), 0) << exact_double(v);
  }
}

TEST(Nsga2, ElitistSurvivalKeepsWholeFrontsThenTheLeastCrowded) {
  const auto problem = make_test_problem("zdt1");
  std::unique_ptr<Nsga2> engine;
  ASSERT_TRUE(Nsga2::create(small_settings(), problem->shape(), std::nullopt, engine).is_ok());
  run_to_end(*problem, *engine, Order::kForward, 3);
  // Merge parents and children by hand and check that the survivors are what NSGA-II keeps.
  std::vector<Individual> merged = engine->population();
  for (const Candidate& c : engine->ask()) {
    ASSERT_TRUE(engine->tell(c.id, problem->evaluate(c.genome)).is_ok());
  }
  for (const Individual& ind : engine->batch()) merged.push_back(ind);
  ASSERT_TRUE(engine->advance().is_ok());
  Points f;
  for (const Individual& ind : merged) f.push_back(ind.result.objectives);
  std::vector<double> violation(f.size(), 0.0);
  const std::vector<int> ranks = constrained_ranks(f, violation);
  std::set<std::uint64_t> survivors;
  int worst_rank = 0;
  for (const Individual& ind : engine->population()) {
    survivors.insert(ind.id);
    worst_rank = std::max(worst_rank, ind.rank);
  }
  ASSERT_EQ(survivors.size(), 20u);
  std::vector<double> crowd(f.size(), 0.0);
  for (const auto& front : fronts_from_ranks(ranks)) crowding_distances(f, front, crowd);
  double min_kept = INFINITY;
  double max_dropped = -INFINITY;
  for (std::size_t i = 0; i < merged.size(); ++i) {
    const bool kept = survivors.count(merged[i].id) != 0;
    if (ranks[i] < worst_rank) {
      EXPECT_TRUE(kept);
    }
    if (ranks[i] > worst_rank) {
      EXPECT_FALSE(kept);
    }
    if (ranks[i] == worst_rank) {
      if (kept)
        min_kept = std::min(min_kept, crowd[i]);
      else
        max_dropped = std::max(max_dropped, crowd[i]);
    }
  }
  EXPECT_GE(min_kept, max_dropped);
}

}  // namespace
}  // namespace stride::opt
