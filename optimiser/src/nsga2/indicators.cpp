// Hypervolume (exact, any M), IGD, normalisation.
#include "stride/optimiser/nsga2/indicators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stride::opt {
namespace {

/// Area dominated by 2-D points (all strictly inside the reference box), by a sweep in f1.
double area_2d(std::vector<std::pair<double, double>> pts, double r0, double r1) {
  std::sort(pts.begin(), pts.end());
  double area = 0.0;
  double best = r1;
  for (const auto& [f0, f1] : pts) {
    if (f1 < best) {
      area += (r0 - f0) * (best - f1);
      best = f1;
    }
  }
  return area;
}

/// Exact hypervolume of points (all strictly dominating ref) in the first `dims` objectives.
double hv_recursive(std::vector<const std::vector<double>*> pts, const std::vector<double>& ref,
                    std::size_t dims) {
  if (pts.empty()) return 0.0;
  if (dims == 1) {
    double best = ref[0];
    for (const auto* p : pts) best = std::min(best, (*p)[0]);
    return ref[0] - best;
  }
  if (dims == 2) {
    std::vector<std::pair<double, double>> flat;
    flat.reserve(pts.size());
    for (const auto* p : pts) flat.emplace_back((*p)[0], (*p)[1]);
    return area_2d(std::move(flat), ref[0], ref[1]);
  }
  const std::size_t last = dims - 1;
  std::sort(pts.begin(), pts.end(),
            [last](const auto* a, const auto* b) { return (*a)[last] < (*b)[last]; });
  double volume = 0.0;
  std::vector<const std::vector<double>*> slice;
  slice.reserve(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    slice.push_back(pts[i]);
    const double top = i + 1 < pts.size() ? (*pts[i + 1])[last] : ref[last];
    const double depth = top - (*pts[i])[last];
    if (depth <= 0.0) continue;
    volume += depth * hv_recursive(slice, ref, last);
  }
  return volume;
}

}  // namespace

double hypervolume(const Points& points, const std::vector<double>& reference) {
  std::vector<const std::vector<double>*> inside;
  for (const auto& p : points) {
    bool strictly = p.size() == reference.size();
    for (std::size_t m = 0; strictly && m < p.size(); ++m) strictly = p[m] < reference[m];
    if (strictly) inside.push_back(&p);
  }
  return hv_recursive(std::move(inside), reference, reference.size());
}

double igd(const Points& set, const Points& reference_front) {
  if (set.empty()) return std::numeric_limits<double>::infinity();
  if (reference_front.empty()) return 0.0;
  double sum = 0.0;
  for (const auto& r : reference_front) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& a : set) {
      double d2 = 0.0;
      for (std::size_t m = 0; m < r.size(); ++m) d2 += (a[m] - r[m]) * (a[m] - r[m]);
      best = std::min(best, d2);
    }
    sum += std::sqrt(best);
  }
  return sum / static_cast<double>(reference_front.size());
}

Points normalise(const Points& points, const std::vector<double>& ideal,
                 const std::vector<double>& nadir) {
  Points out = points;
  for (auto& p : out) {
    for (std::size_t m = 0; m < p.size(); ++m) {
      const double range = nadir[m] - ideal[m];
      p[m] = range > 0.0 ? (p[m] - ideal[m]) / range : p[m] - ideal[m];
    }
  }
  return out;
}

Points non_dominated(const Points& points) {
  const std::vector<int> ranks = pareto_ranks(points);
  Points out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (ranks[i] == 0) out.push_back(points[i]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace stride::opt
