// Test problems: known Pareto-optimal points land on the front formulas; reference fronts are
// feasible and non-dominated with the expected hypervolumes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "stride/optimiser/nsga2/indicators.hpp"
#include "stride/optimiser/problems/test_problems.hpp"

namespace stride::opt {
namespace {

EvaluationOutcome eval(const std::string& name, std::vector<double> x) {
  Genome g;
  g.reals = std::move(x);
  return make_test_problem(name)->evaluate(g);
}

TEST(TestProblems, ParetoOptimalPointsLieOnTheFront) {
  std::vector<double> x(30, 0.0);
  x[0] = 0.25;
  EXPECT_NEAR(eval("zdt1", x).objectives[1], 0.5, 1e-15);
  EXPECT_NEAR(eval("zdt2", x).objectives[1], 1 - 0.0625, 1e-15);
  EXPECT_NEAR(eval("zdt3", x).objectives[1], 0.25, 1e-15);  // 1 - 0.5 - 0.25 sin(2.5 pi)
  std::vector<double> x10(10, 0.0);
  x10[0] = 0.25;
  EXPECT_NEAR(eval("zdt4", x10).objectives[1], 0.5, 1e-12);  // g = 1 + 90 - 90
  x10[0] = 0.5;
  const auto z6 = eval("zdt6", x10);  // sin(3 pi) = 0: f1 = 1, f2 = 0
  EXPECT_NEAR(z6.objectives[0], 1.0, 1e-12);
  EXPECT_NEAR(z6.objectives[1], 0.0, 1e-12);
  std::vector<double> d1 = {1, 1, 0.5, 0.5, 0.5, 0.5, 0.5};
  const auto o1 = eval("dtlz1", d1).objectives;
  EXPECT_NEAR(o1[0], 0.5, 1e-12);
  EXPECT_NEAR(o1[1] + o1[2], 0.0, 1e-12);
  std::vector<double> d2(12, 0.5);
  d2[0] = 0.5;
  d2[1] = 0.5;
  const auto o2 = eval("dtlz2", d2).objectives;
  EXPECT_NEAR(o2[0] * o2[0] + o2[1] * o2[1] + o2[2] * o2[2], 1.0, 1e-12);
  const auto b = eval("bnh", {1, 1});
  EXPECT_EQ(b.objectives, (std::vector<double>{8, 32}));
  EXPECT_NEAR(b.constraints[0], 8, 1e-12);
  EXPECT_NEAR(b.constraints[1], 57.3, 1e-12);
  const auto s = eval("srn", {0, 0});  // g2 = -10 - 0 + 0 < 0: infeasible
  EXPECT_LT(s.constraints[1], 0);
  const auto t = eval("tnk", {1, 1});
  EXPECT_GT(t.constraints[0], 0);
  EXPECT_NEAR(t.constraints[1], 0.0, 1e-15);
  const auto o = eval("osy", {5, 1, 1, 0, 1, 0});
  EXPECT_NEAR(o.objectives[0], -(25 * 9 + 1 + 16), 1e-12);
  EXPECT_NEAR(o.objectives[1], 28, 1e-12);
}

TEST(TestProblems, ReferenceFrontsAreConsistent) {
  for (const std::string& name : test_problem_names()) {
    const auto problem = make_test_problem(name);
    ASSERT_NE(problem, nullptr) << name;
    EXPECT_EQ(problem->name(), name);
    const auto ref = problem->reference();
    ASSERT_TRUE(ref.has_value()) << name;
    EXPECT_GE(ref->front.size(), 200u) << name;
    EXPECT_LE(ref->front.size(), 2100u) << name;
    EXPECT_EQ(non_dominated(ref->front).size(), ref->front.size()) << name;
    for (std::size_t m = 0; m < ref->ideal.size(); ++m) EXPECT_LT(ref->ideal[m], ref->nadir[m]);
    ASSERT_TRUE(ref->true_hypervolume.has_value());
    EXPECT_GT(*ref->true_hypervolume, 0.3) << name;
    EXPECT_LT(*ref->true_hypervolume, 1.331) << name;
  }
  EXPECT_EQ(make_test_problem("zdt5"), nullptr);
  EXPECT_EQ(make_test_problem("nope"), nullptr);
}

TEST(TestProblems, TrueHypervolumesMatchTheAnalyticValues) {
  // Normalised, reference 1.1: ZDT1 0.1 + 2/3 + 0.11; ZDT2 0.1 + 1/3 + 0.11.
  EXPECT_NEAR(*make_test_problem("zdt1")->reference()->true_hypervolume, 0.21 + 2.0 / 3, 1e-4);
  EXPECT_NEAR(*make_test_problem("zdt2")->reference()->true_hypervolume, 0.21 + 1.0 / 3, 1e-4);
  EXPECT_NEAR(*make_test_problem("zdt4")->reference()->true_hypervolume, 0.21 + 2.0 / 3, 1e-4);
  EXPECT_NEAR(*make_test_problem("dtlz2")->reference()->true_hypervolume,
              1.331 - std::numbers::pi / 6, 1e-12);
  // The DTLZ samples approach the analytic value from below.
  const auto ref = make_test_problem("dtlz1")->reference();
  const double sampled =
      hypervolume(normalise(ref->front, ref->ideal, ref->nadir), {1.1, 1.1, 1.1});
  EXPECT_LT(sampled, *ref->true_hypervolume);
  EXPECT_GT(sampled, *ref->true_hypervolume - 0.05);
}

}  // namespace
}  // namespace stride::opt
