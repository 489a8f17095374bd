// pareto.csv, the non-dominated filter, the knee point and the pick names (pareto_front.hpp).
#include "stride/optimiser/report/pareto_front.hpp"
#include "stride/optimiser/tasks/task_type.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace stride::opt {

namespace fs = std::filesystem;

std::vector<std::vector<double>> non_dominated(std::vector<std::vector<double>> points) {
  std::sort(points.begin(), points.end());
  std::vector<std::vector<double>> front;
  double best_f2 = std::numeric_limits<double>::infinity();
  for (const auto& p : points) {
    if (p[1] < best_f2) {
      if (!front.empty() && front.back()[0] == p[0]) front.pop_back();
      front.push_back(p);
      best_f2 = p[1];
    }
  }
  return front;
}

std::size_t knee_index(const std::vector<std::vector<double>>& front) {
  if (front.empty()) return 0;
  std::vector<double> lo(front[0].size(), std::numeric_limits<double>::infinity());
  std::vector<double> hi(front[0].size(), -std::numeric_limits<double>::infinity());
  for (const auto& p : front)
    for (std::size_t m = 0; m < p.size(); ++m)
      lo[m] = std::min(lo[m], p[m]), hi[m] = std::max(hi[m], p[m]);
  std::size_t best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < front.size(); ++i) {
    double d = 0.0;
    for (std::size_t m = 0; m < front[i].size(); ++m) {
      const double range = hi[m] - lo[m];
      const double z = range > 0 ? (front[i][m] - lo[m]) / range : 0.0;
      d += z * z;
    }
    if (d < best_d) best_d = d, best = i;
  }
  return best;
}

Status read_pareto_csv(const fs::path& path, int objectives, std::vector<FrontMember>& out) {
  std::ifstream in(path);
  if (!in) return Status::error(path.string() + ": cannot open");
  std::string line;
  out.clear();
  if (!std::getline(in, line)) return Status::error(path.string() + ": empty");
  std::size_t row = 1;
  while (std::getline(in, line)) {
    ++row;
    if (line.empty()) continue;
    std::stringstream cells(line);
    std::string cell;
    FrontMember m;
    int column = 0;
    while (std::getline(cells, cell, ',')) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (cell.empty() || *end != '\0')
        return Status::error(path.string() + ": row " + std::to_string(row) +
                             " has a non-number '" + cell + "'");
      (column < objectives ? m.objectives : m.genes).push_back(v);
      ++column;
    }
    out.push_back(std::move(m));
  }
  return {};
}

RunPickNames run_pick_names(const std::string& task) {
  if (const TaskType* type = find_task_type(task))
    return {type->descriptor().best_f1_pick, type->descriptor().best_f2_pick};
  return {"best_obj1", "best_obj2"};
}

}  // namespace stride::opt
