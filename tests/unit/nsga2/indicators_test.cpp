// Hypervolume (2, 3 and more objectives) and IGD against hand-computed values and
// inclusion-exclusion.
#include <gtest/gtest.h>

#include <cmath>

#include "stride/optimiser/nsga2/indicators.hpp"
#include "stride/optimiser/nsga2/rng.hpp"

namespace stride::opt {
namespace {

/// Exact hypervolume by inclusion-exclusion over all subsets (small sets only).
double inclusion_exclusion(const Points& pts, const std::vector<double>& ref) {
  double total = 0;
  const std::size_t n = pts.size();
  for (std::uint32_t mask = 1; mask < (1u << n); ++mask) {
    std::vector<double> corner(ref.size(), -1e300);
    int bits = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (!(mask & (1u << i))) continue;
      ++bits;
      for (std::size_t m = 0; m < ref.size(); ++m) corner[m] = std::max(corner[m], pts[i][m]);
    }
    double volume = 1;
    for (std::size_t m = 0; m < ref.size(); ++m) volume *= std::max(0.0, ref[m] - corner[m]);
    total += (bits % 2 ? 1 : -1) * volume;
  }
  return total;
}

TEST(Hypervolume, TwoObjectivesByHand) {
  EXPECT_DOUBLE_EQ(hypervolume({{1, 3}, {2, 2}, {3, 1}}, {4, 4}), 6.0);
  // dominated, duplicate and outside points add nothing
  EXPECT_DOUBLE_EQ(hypervolume({{1, 3}, {2, 2}, {3, 1}, {3, 3}, {2, 2}, {5, 0}, {0, 4}}, {4, 4}),
                   6.0);
  EXPECT_DOUBLE_EQ(hypervolume({}, {1, 1}), 0.0);
}

TEST(Hypervolume, ThreeObjectivesByHand) {
  EXPECT_DOUBLE_EQ(hypervolume({{1, 1, 1}}, {2, 2, 2}), 1.0);
  // 2*2*1 + 1*1*2 - 1*1*1
  EXPECT_DOUBLE_EQ(hypervolume({{0, 0, 1}, {1, 1, 0}}, {2, 2, 2}), 5.0);
}

TEST(Hypervolume, MatchesInclusionExclusionUpToFiveObjectives) {
  Rng rng(23);
  for (std::size_t m = 2; m <= 5; ++m) {
    for (int trial = 0; trial < 30; ++trial) {
      Points pts(8, std::vector<double>(m));
      for (auto& p : pts) {
        for (double& v : p) v = std::floor(rng.uniform01() * 12) / 10;  // some ties, some > ref
      }
      const std::vector<double> ref(m, 1.0);
      Points inside;
      for (const auto& p : pts) {
        bool ok = true;
        for (std::size_t k = 0; k < m; ++k) ok = ok && p[k] < 1.0;
        if (ok) inside.push_back(p);
      }
      EXPECT_NEAR(hypervolume(pts, ref), inclusion_exclusion(inside, ref), 1e-12) << "M=" << m;
    }
  }
}

TEST(Igd, ByHand) {
  const Points front = {{0, 1}, {1, 0}};
  EXPECT_NEAR(igd({{0, 1}}, front), std::sqrt(2.0) / 2, 1e-15);
  EXPECT_DOUBLE_EQ(igd(front, front), 0.0);
  EXPECT_TRUE(std::isinf(igd({}, front)));
}

TEST(Indicators, NormaliseAndNonDominated) {
  const Points n = normalise({{1, 10}, {3, 30}}, {1, 10}, {3, 30});
  EXPECT_EQ(n, (Points{{0, 0}, {1, 1}}));
  EXPECT_EQ(non_dominated({{2, 1}, {1, 2}, {2, 2}, {1, 2}}), (Points{{1, 2}, {2, 1}}));
}

}  // namespace
}  // namespace stride::opt
