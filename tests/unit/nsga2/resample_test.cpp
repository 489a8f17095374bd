// The NSGA-II engine on a noisy problem: resampling (a new draw each generation, the parents
// evaluated again beside their children), and several start genomes.
#include <gtest/gtest.h>

#include <cstring>

#include "stride/optimiser/nsga2/nsga2.hpp"
#include "stride/optimiser/problems/test_problems.hpp"

namespace stride::opt {
namespace {

/// ZDT1 plus noise of up to 0.2 that depends on the draw and the genome's bits, as a robot
/// task's trial worlds do.
class NoisyZdt1 final : public Problem {
 public:
  std::string name() const override { return "noisy-zdt1"; }
  const ProblemShape& shape() const override { return inner_->shape(); }
  EvaluationOutcome evaluate(const Genome& g) const override { return evaluate_on(g, 0); }
  EvaluationOutcome evaluate_on(const Genome& g, std::uint64_t draw) const override {
    EvaluationOutcome o = inner_->evaluate(g);
    std::uint64_t h = draw * 0x9E3779B97F4A7C15ull + 1;
    for (const double x : g.reals) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &x, sizeof bits);
      h = (h ^ bits) * 0xBF58476D1CE4E5B9ull;
      h ^= h >> 31;
    }
    for (double& f : o.objectives) {
      f += 0.2 * static_cast<double>(h % 1000) / 1000.0;
      h = h * 6364136223846793005ull + 1442695040888963407ull;
    }
    return o;
  }

 private:
  std::unique_ptr<Problem> inner_ = make_test_problem("zdt1");
};

Nsga2Settings resampling(bool on) {
  Nsga2Settings s;
  s.seed = 11;
  s.pop_size = 16;
  s.generations = 6;
  s.real_mut_prob = 1.0 / 30;
  s.resample = on;
  return s;
}

/// Runs to the end, each candidate on its own draw; every told result is recorded.
nlohmann::json run(const Problem& problem, Nsga2& engine, int until = -1) {
  while (!engine.finished() && (until < 0 || engine.completed_generations() < until)) {
    for (const Candidate& c : engine.ask())
      EXPECT_TRUE(engine.tell(c.id, problem.evaluate_on(c.genome, c.draw)).is_ok());
    EXPECT_TRUE(engine.advance().is_ok());
  }
  return engine.checkpoint();
}

TEST(Nsga2Resample, EachGenerationHasItsDrawAndTheParentsAreEvaluatedAgainOnIt) {
  const NoisyZdt1 problem;
  std::unique_ptr<Nsga2> engine;
  ASSERT_TRUE(Nsga2::create(resampling(true), problem.shape(), std::nullopt, engine).is_ok());
  EXPECT_EQ(engine->batch_draw(), 0u);
  EXPECT_EQ(engine->batch().size(), 16u);
  for (int g = 1; g < 6; ++g) {
    run(problem, *engine, g);
    ASSERT_EQ(engine->batch_draw(), static_cast<std::uint64_t>(g));
    // The batch: 16 children, then the 16 parents again.
    const std::vector<Individual>& batch = engine->batch();
    ASSERT_EQ(batch.size(), 32u);
    for (std::size_t i = 0; i < 16; ++i)
      EXPECT_EQ(batch[16 + i].genome, engine->population()[i].genome) << "generation " << g;
    for (const Candidate& c : engine->ask()) EXPECT_EQ(c.draw, static_cast<std::uint64_t>(g));
  }
  run(problem, *engine);
  // Every survivor's result is its score on the last generation's draw, whatever it scored
  // before: no genome lives on an earlier, luckier draw.
  for (const Individual& ind : engine->population()) {
    const EvaluationOutcome again = problem.evaluate_on(ind.genome, 5);
    EXPECT_EQ(ind.result.objectives, again.objectives);
  }
}

TEST(Nsga2Resample, WithoutItEveryDrawIsZeroAndTheBatchIsTheChildren) {
  const NoisyZdt1 problem;
  std::unique_ptr<Nsga2> engine;
  ASSERT_TRUE(Nsga2::create(resampling(false), problem.shape(), std::nullopt, engine).is_ok());
  run(problem, *engine, 3);
  EXPECT_EQ(engine->batch_draw(), 0u);
  EXPECT_EQ(engine->batch().size(), 16u);
  EXPECT_EQ(engine->checkpoint()["settings"].count("resample"), 0u);  // old checkpoints equal
}

TEST(Nsga2Resample, RestoreFromACheckpointReproducesTheUninterruptedRun) {
  const NoisyZdt1 problem;
  std::unique_ptr<Nsga2> full;
  ASSERT_TRUE(Nsga2::create(resampling(true), problem.shape(), std::nullopt, full).is_ok());
  const nlohmann::json expected = run(problem, *full);
  EXPECT_EQ(expected["settings"]["resample"], true);
  for (const int stop : {0, 1, 4}) {
    std::unique_ptr<Nsga2> first;
    ASSERT_TRUE(Nsga2::create(resampling(true), problem.shape(), std::nullopt, first).is_ok());
    std::vector<std::pair<Genome, Result>> known;
    while (first->completed_generations() < stop) {
      for (const Candidate& c : first->ask()) {
        ASSERT_TRUE(first->tell(c.id, problem.evaluate_on(c.genome, c.draw)).is_ok());
        known.emplace_back(c.genome, first->batch_member(c.id)->result);
      }
      ASSERT_TRUE(first->advance().is_ok());
    }
    const nlohmann::json cp = nlohmann::json::parse(first->checkpoint().dump());
    std::unique_ptr<Nsga2> resumed;
    ASSERT_TRUE(Nsga2::restore(cp, problem.shape(), known, resumed).is_ok());
    // The earlier draws' results do not serve the batch after the checkpoint.
    EXPECT_EQ(resumed->ask().size(), first->ask().size()) << "stop " << stop;
    EXPECT_EQ(run(problem, *resumed), expected) << "stop " << stop;
  }
}

TEST(Nsga2Starts, TheStartsLeadThePopulationAndOneStartIsTheSingleStartRun) {
  const auto problem = make_test_problem("zdt1");
  std::vector<Genome> starts(3);
  for (std::size_t k = 0; k < starts.size(); ++k)
    starts[k].reals.assign(30, 0.2 + 0.3 * static_cast<double>(k));
  Nsga2Settings s = resampling(false);
  s.seed_mutation_fraction = 0.5;
  std::unique_ptr<Nsga2> engine;
  ASSERT_TRUE(Nsga2::create(s, problem->shape(), starts, engine).is_ok());
  const std::vector<Individual>& batch = engine->batch();
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(batch[k].genome, starts[k]);
  // The others are mutated copies of the starts in turn: most genes still the start's value.
  for (std::size_t i = 3; i < batch.size(); ++i) {
    const double value = starts[(i - 3) % 3].reals[0];
    int kept = 0;
    for (const double v : batch[i].genome.reals) kept += v == value;
    EXPECT_GT(kept, 5) << "member " << i;
  }
  std::unique_ptr<Nsga2> one, single;
  ASSERT_TRUE(Nsga2::create(s, problem->shape(), std::vector<Genome>{starts[1]}, one).is_ok());
  ASSERT_TRUE(Nsga2::create(s, problem->shape(), starts[1], single).is_ok());
  EXPECT_EQ(one->checkpoint(), single->checkpoint());

  starts[2].reals[4] = 1.5;
  const Status bad = Nsga2::create(s, problem->shape(), starts, engine);
  ASSERT_FALSE(bad.is_ok());
  EXPECT_EQ(bad.message().rfind("start 3: ", 0), 0u) << bad.message();
  s.pop_size = 4;
  starts.resize(5, starts[0]);
  EXPECT_FALSE(Nsga2::create(s, problem->shape(), starts, engine).is_ok());
}

}  // namespace
}  // namespace stride::opt
