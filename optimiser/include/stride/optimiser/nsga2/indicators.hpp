// Quality indicators of a set of objective vectors (minimised).
//
// hypervolume(): the Lebesgue measure of the region dominated by the set and bounded by the
// reference point; points that do not strictly dominate the reference contribute nothing.
// Exact for every number of objectives: a sweep in O(N log N) for two, slicing along the
// third objective into two-dimensional sweeps (O(N^2 log N)) for three, and recursive slicing
// along the last objective (exponential in M, fine for population-sized sets) beyond.
//
// igd(): inverted generational distance, the mean over the reference front of the Euclidean
// distance to the nearest member of the set (lower is better; +infinity for an empty set).
//
// normalise(): (f - ideal) / (nadir - ideal) per objective, the space in which Stride reports
// both indicators (reference point 1.1 per objective).
#pragma once

#include <vector>

#include "stride/optimiser/nsga2/sorting.hpp"

namespace stride::opt {

double hypervolume(const Points& points, const std::vector<double>& reference);
double igd(const Points& set, const Points& reference_front);
Points normalise(const Points& points, const std::vector<double>& ideal,
                 const std::vector<double>& nadir);
/// The non-dominated members of a set, duplicates kept once, sorted lexicographically.
Points non_dominated(const Points& points);

}  // namespace stride::opt
