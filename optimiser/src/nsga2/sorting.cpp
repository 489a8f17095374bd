// Non-dominated sorting (Deb's, 2-D sweep, ENS-BS) and crowding distance.
#include "stride/optimiser/nsga2/sorting.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <utility>

namespace stride::opt {
namespace {

/// Indices sorted lexicographically by all objectives (ties by index).
std::vector<int> lexicographic_order(const Points& points) {
  std::vector<int> order(points.size());
  if (!points.empty() && points.front().size() == 2) {
    // The common two-objective case: sort contiguous (f1, f2, index) keys. The order is total
    // (ties by index), so it is the same order as the general comparator below gives.
    struct Key {
      double f1, f2;
      int index;
    };
    std::vector<Key> keys(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      keys[i] = {points[i][0], points[i][1], static_cast<int>(i)};
    std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
      if (a.f1 != b.f1) return a.f1 < b.f1;
      if (a.f2 != b.f2) return a.f2 < b.f2;
      return a.index < b.index;
    });
    for (std::size_t i = 0; i < keys.size(); ++i) order[i] = keys[i].index;
    return order;
  }
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const auto& pa = points[static_cast<std::size_t>(a)];
    const auto& pb = points[static_cast<std::size_t>(b)];
    for (std::size_t m = 0; m < pa.size(); ++m) {
      if (pa[m] < pb[m]) return true;
      if (pb[m] < pa[m]) return false;
    }
    return a < b;
  });
  return order;
}

/// For q lexicographically before p: q dominates p iff q <= p everywhere and q != p.
bool earlier_dominates(const std::vector<double>& q, const std::vector<double>& p) {
  bool strictly = false;
  for (std::size_t m = 0; m < q.size(); ++m) {
    if (q[m] > p[m]) return false;
    if (q[m] < p[m]) strictly = true;
  }
  return strictly;
}

}  // namespace

bool dominates(const std::vector<double>& a, const std::vector<double>& b) {
  bool better = false;
  for (std::size_t m = 0; m < a.size(); ++m) {
    if (a[m] > b[m]) return false;
    if (a[m] < b[m]) better = true;
  }
  return better;
}

int constrained_dominance(const std::vector<double>& a, double violation_a,
                          const std::vector<double>& b, double violation_b) {
  if (violation_a > 0.0 || violation_b > 0.0) {
    if (violation_a < violation_b) return 1;
    if (violation_b < violation_a) return -1;
    if (violation_a > 0.0) return 0;  // equally infeasible
  }
  if (dominates(a, b)) return 1;
  if (dominates(b, a)) return -1;
  return 0;
}

std::vector<int> fast_non_dominated_sort(const Points& points) {
  const std::size_t n = points.size();
  std::vector<std::vector<int>> dominated(n);
  std::vector<int> count(n, 0);
  std::vector<int> rank(n, 0);
  std::vector<int> current;
  for (std::size_t p = 0; p < n; ++p) {
    for (std::size_t q = 0; q < n; ++q) {
      if (p == q) continue;
      if (dominates(points[p], points[q])) {
        dominated[p].push_back(static_cast<int>(q));
      } else if (dominates(points[q], points[p])) {
        ++count[p];
      }
    }
    if (count[p] == 0) current.push_back(static_cast<int>(p));
  }
  int front = 0;
  while (!current.empty()) {
    std::vector<int> next;
    for (const int p : current) {
      rank[static_cast<std::size_t>(p)] = front;
      for (const int q : dominated[static_cast<std::size_t>(p)]) {
        if (--count[static_cast<std::size_t>(q)] == 0) next.push_back(q);
      }
    }
    current = std::move(next);
    ++front;
  }
  return rank;
}

std::vector<int> sweep_sort_2d(const Points& points) {
  std::vector<int> rank(points.size(), 0);
  std::vector<const std::vector<double>*> last;  // last member of each front
  for (const int index : lexicographic_order(points)) {
    const std::vector<double>& p = points[static_cast<std::size_t>(index)];
    // First front whose last member (the smallest f2 in it) does not dominate p.
    std::size_t lo = 0;
    std::size_t hi = last.size();
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      const std::vector<double>& l = *last[mid];
      const bool dominated = l[1] < p[1] || (l[1] == p[1] && l[0] < p[0]);
      if (dominated) {
        lo = mid + 1;
      } else {
        hi = mid;
      }
    }
    if (lo == last.size()) {
      last.push_back(&p);
    } else {
      last[lo] = &p;
    }
    rank[static_cast<std::size_t>(index)] = static_cast<int>(lo);
  }
  return rank;
}

std::vector<int> efficient_sort(const Points& points) {
  std::vector<int> rank(points.size(), 0);
  std::vector<std::vector<int>> fronts;
  for (const int index : lexicographic_order(points)) {
    const std::vector<double>& p = points[static_cast<std::size_t>(index)];
    auto dominated_by = [&](std::size_t k) {
      const std::vector<int>& members = fronts[k];
      for (auto it = members.rbegin(); it != members.rend(); ++it) {
        if (earlier_dominates(points[static_cast<std::size_t>(*it)], p)) return true;
      }
      return false;
    };
    std::size_t lo = 0;
    std::size_t hi = fronts.size();
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      if (dominated_by(mid)) {
        lo = mid + 1;
      } else {
        hi = mid;
      }
    }
    if (lo == fronts.size()) fronts.emplace_back();
    fronts[lo].push_back(index);
    rank[static_cast<std::size_t>(index)] = static_cast<int>(lo);
  }
  return rank;
}

std::vector<int> pareto_ranks(const Points& points) {
  if (points.empty()) return {};
  if (points.front().size() == 2) return sweep_sort_2d(points);
  return efficient_sort(points);
}

std::vector<int> constrained_ranks(const Points& points, const std::vector<double>& violations) {
  // All feasible (the common case): the Pareto ranks themselves, without copying the points.
  if (std::none_of(violations.begin(), violations.end(), [](double v) { return v > 0.0; }))
    return pareto_ranks(points);
  std::vector<int> rank(points.size(), 0);
  Points feasible;
  std::vector<int> feasible_index;
  std::vector<int> infeasible_index;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (violations[i] > 0.0) {
      infeasible_index.push_back(static_cast<int>(i));
    } else {
      feasible.push_back(points[i]);
      feasible_index.push_back(static_cast<int>(i));
    }
  }
  int next_rank = 0;
  const std::vector<int> feasible_rank = pareto_ranks(feasible);
  for (std::size_t k = 0; k < feasible_index.size(); ++k) {
    rank[static_cast<std::size_t>(feasible_index[k])] = feasible_rank[k];
    next_rank = std::max(next_rank, feasible_rank[k] + 1);
  }
  std::stable_sort(infeasible_index.begin(), infeasible_index.end(), [&](int a, int b) {
    return violations[static_cast<std::size_t>(a)] < violations[static_cast<std::size_t>(b)];
  });
  for (std::size_t k = 0; k < infeasible_index.size(); ++k) {
    if (k > 0 && violations[static_cast<std::size_t>(infeasible_index[k])] >
                     violations[static_cast<std::size_t>(infeasible_index[k - 1])]) {
      ++next_rank;
    }
    rank[static_cast<std::size_t>(infeasible_index[k])] = next_rank;
  }
  return rank;
}

std::vector<std::vector<int>> fronts_from_ranks(const std::vector<int>& ranks) {
  std::vector<std::vector<int>> fronts;
  for (std::size_t i = 0; i < ranks.size(); ++i) {
    const auto r = static_cast<std::size_t>(ranks[i]);
    if (r >= fronts.size()) fronts.resize(r + 1);
    fronts[r].push_back(static_cast<int>(i));
  }
  return fronts;
}

void crowding_distances(const Points& points, const std::vector<int>& front,
                        std::vector<double>& distance) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (const int i : front) distance[static_cast<std::size_t>(i)] = 0.0;
  if (front.size() <= 2) {
    for (const int i : front) distance[static_cast<std::size_t>(i)] = kInf;
    return;
  }
  const std::size_t objectives = points[static_cast<std::size_t>(front.front())].size();
  // Per objective, the members sorted by (value, index): a total order, on contiguous keys.
  std::vector<std::pair<double, int>> sorted(front.size());
  for (std::size_t m = 0; m < objectives; ++m) {
    for (std::size_t k = 0; k < front.size(); ++k)
      sorted[k] = {points[static_cast<std::size_t>(front[k])][m], front[k]};
    std::sort(sorted.begin(), sorted.end());
    const double lo = sorted.front().first;
    const double hi = sorted.back().first;
    distance[static_cast<std::size_t>(sorted.front().second)] = kInf;
    distance[static_cast<std::size_t>(sorted.back().second)] = kInf;
    const double range = hi - lo;
    if (!(range > 0.0)) continue;
    for (std::size_t k = 1; k + 1 < sorted.size(); ++k) {
      const double gap = sorted[k + 1].first - sorted[k - 1].first;
      distance[static_cast<std::size_t>(sorted[k].second)] += gap / range;
    }
  }
}

}  // namespace stride::opt
