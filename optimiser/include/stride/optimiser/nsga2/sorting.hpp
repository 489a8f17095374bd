// Non-dominated sorting and crowding distance (all objectives minimised).
//
// Pareto dominance: a dominates b if a is no worse in every objective and better in one.
// Constraint domination (Deb): a feasible point beats an infeasible one; of two infeasible
// points the smaller violation wins; two feasible points compare by Pareto dominance.
//
// Ranks are 0-based front indices (0 = non-dominated). Three Pareto sorts give the same ranks:
//   fast_non_dominated_sort  Deb's O(M N^2) method with domination counts (the seed's
//                            Algorithm 1); memory O(N^2), the reference for small sets;
//   sweep_sort_2d            O(N log N) for two objectives: a lexicographic sweep that puts each
//                            point in the first front whose last member does not dominate it;
//   efficient_sort           ENS with binary search over fronts (Zhang et al. 2015), any M.
// pareto_ranks() picks the sweep for two objectives and ENS otherwise.
#pragma once

#include <vector>

namespace stride::opt {

using Points = std::vector<std::vector<double>>;

/// True if a Pareto-dominates b.
bool dominates(const std::vector<double>& a, const std::vector<double>& b);

/// +1 if a constraint-dominates b, -1 if b constraint-dominates a, 0 otherwise.
int constrained_dominance(const std::vector<double>& a, double violation_a,
                          const std::vector<double>& b, double violation_b);

std::vector<int> fast_non_dominated_sort(const Points& points);
std::vector<int> sweep_sort_2d(const Points& points);
std::vector<int> efficient_sort(const Points& points);
std::vector<int> pareto_ranks(const Points& points);

/// Ranks under constraint domination: feasible points (violation 0) by pareto_ranks(), then the
/// infeasible ones in fronts of equal violation, smaller violation first.
std::vector<int> constrained_ranks(const Points& points, const std::vector<double>& violations);

/// The members of each front (indices ascending) from ranks.
std::vector<std::vector<int>> fronts_from_ranks(const std::vector<int>& ranks);

/// Crowding distance of the members of one front, written to distance[member]. Boundary points
/// (and every point of a front of one or two) get +infinity; interior points sum, over the
/// objectives, the normalised gap (f[next] - f[prev]) / (f_max - f_min) between their
/// neighbours; an objective with f_max == f_min adds nothing. Ties sort by index.
void crowding_distances(const Points& points, const std::vector<int>& front,
                        std::vector<double>& distance);

}  // namespace stride::opt
