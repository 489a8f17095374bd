// Non-dominated sorting (three methods), constraint domination and crowding distance.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "stride/optimiser/nsga2/rng.hpp"
#include "stride/optimiser/nsga2/sorting.hpp"

namespace stride::opt {
namespace {

const double kInf = std::numeric_limits<double>::infinity();

TEST(Sorting, HandExampleInTwoObjectives) {
  const Points pts = {{1, 5}, {2, 3}, {3, 1}, {2, 4}, {4, 4}, {5, 5}, {2, 3}};
  // (2,4) is dominated only by (2,3); (4,4) also by (2,4); (5,5) by (4,4); duplicates share.
  const std::vector<int> expected = {0, 0, 0, 1, 2, 3, 0};
  EXPECT_EQ(fast_non_dominated_sort(pts), expected);
  EXPECT_EQ(sweep_sort_2d(pts), expected);
  EXPECT_EQ(efficient_sort(pts), expected);
  EXPECT_EQ(pareto_ranks(pts), expected);
}

TEST(Sorting, HandExampleInThreeObjectives) {
  const Points pts = {{1, 2, 3}, {3, 2, 1}, {2, 2, 2}, {2, 3, 3}, {3, 3, 3}, {1, 2, 4}};
  // (2,3,3) <- (1,2,3), (2,2,2); (3,3,3) <- (2,3,3); (1,2,4) <- (1,2,3)
  const std::vector<int> expected = {0, 0, 0, 1, 2, 1};
  EXPECT_EQ(fast_non_dominated_sort(pts), expected);
  EXPECT_EQ(efficient_sort(pts), expected);
}

TEST(Sorting, AllMethodsAgreeOnRandomSetsWithTies) {
  Rng rng(17);
  for (int m = 2; m <= 5; ++m) {
    for (int trial = 0; trial < 20; ++trial) {
      Points pts(200, std::vector<double>(static_cast<std::size_t>(m)));
      for (auto& p : pts) {
        for (double& v : p) v = std::floor(rng.uniform01() * (trial % 2 ? 6 : 1000));  // ties
      }
      const std::vector<int> reference = fast_non_dominated_sort(pts);
      EXPECT_EQ(efficient_sort(pts), reference) << "M=" << m;
      if (m == 2) {
        EXPECT_EQ(sweep_sort_2d(pts), reference);
      }
      // Every point of front k > 0 is dominated by a point of front k-1, none by its own front.
      for (std::size_t i = 0; i < pts.size(); ++i) {
        bool dominated_by_previous = reference[i] == 0;
        for (std::size_t j = 0; j < pts.size(); ++j) {
          if (reference[j] == reference[i]) {
            ASSERT_FALSE(dominates(pts[j], pts[i]));
          }
          if (reference[j] == reference[i] - 1 && dominates(pts[j], pts[i])) {
            dominated_by_previous = true;
          }
        }
        ASSERT_TRUE(dominated_by_previous);
      }
    }
  }
}

TEST(ConstraintDomination, FeasibleFirstThenSmallerViolation) {
  const std::vector<double> good = {0, 0};
  const std::vector<double> bad = {5, 5};
  EXPECT_EQ(constrained_dominance(bad, 0.0, good, 0.1), 1);   // feasible beats infeasible
  EXPECT_EQ(constrained_dominance(good, 0.3, bad, 0.1), -1);  // smaller violation wins
  EXPECT_EQ(constrained_dominance(good, 0.2, bad, 0.2), 0);   // equal violations: no order
  EXPECT_EQ(constrained_dominance(good, 0.0, bad, 0.0), 1);   // both feasible: Pareto
  EXPECT_EQ(constrained_dominance({0, 1}, 0.0, {1, 0}, 0.0), 0);

  const Points pts = {{5, 5}, {0, 0}, {1, 1}, {9, 0}, {0, 9}, {3, 3}};
  const std::vector<double> violation = {0, 0.5, 0.2, 0, 0.5, 0};
  // feasible: (5,5) (9,0) (3,3): (3,3) and (9,0) front 0, (5,5) front 1; then 0.2, then 0.5 x2
  EXPECT_EQ(constrained_ranks(pts, violation), (std::vector<int>{1, 3, 2, 0, 3, 0}));
}

TEST(Crowding, HandExample) {
  // f2 scaled by 10 to check the per-objective normalisation.
  const Points pts = {{0, 10}, {0.1, 6}, {0.5, 2}, {1, 0}, {7, 7}};
  std::vector<double> d(pts.size(), -1.0);
  crowding_distances(pts, {0, 1, 2, 3}, d);
  EXPECT_EQ(d[0], kInf);
  EXPECT_EQ(d[3], kInf);
  EXPECT_NEAR(d[1], 0.5 / 1 + 8.0 / 10, 1e-15);  // f1 gap 0.5, f2 gap (10 - 2) / 10
  EXPECT_NEAR(d[2], 0.9 / 1 + 6.0 / 10, 1e-15);  // f1 gap 0.9, f2 gap (6 - 0) / 10
  EXPECT_EQ(d[4], -1.0);                         // not in the front: untouched
  std::vector<double> two(pts.size(), 0.0);
  crowding_distances(pts, {1, 2}, two);
  EXPECT_EQ(two[1], kInf);
  EXPECT_EQ(two[2], kInf);
  // An objective with no spread adds nothing (and no NaN).
  const Points flat = {{1, 0}, {1, 1}, {1, 2}, {1, 3}};
  std::vector<double> f(4, 0.0);
  crowding_distances(flat, {0, 1, 2, 3}, f);
  EXPECT_NEAR(f[1], 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(f[2], 2.0 / 3.0, 1e-15);
}

TEST(Sorting, FrontsFromRanks) {
  const auto fronts = fronts_from_ranks({2, 0, 1, 0, 2});
  ASSERT_EQ(fronts.size(), 3u);
  EXPECT_EQ(fronts[0], (std::vector<int>{1, 3}));
  EXPECT_EQ(fronts[1], (std::vector<int>{2}));
  EXPECT_EQ(fronts[2], (std::vector<int>{0, 4}));
}

}  // namespace
}  // namespace stride::opt
