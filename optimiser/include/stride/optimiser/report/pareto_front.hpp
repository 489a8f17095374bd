// A run's Pareto front as the run directory keeps it (pareto.csv) and the choices made on it:
// the non-dominated filter, the knee point and the names of the best member per objective. Below
// both the run directory (run/) and the report (report/), which read it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "stride/core/status.hpp"

namespace stride::opt {

/// One row of pareto.csv.
struct FrontMember {
  std::vector<double> objectives;
  std::vector<double> genes;
  /// A resampling run's score of this row on fresh worlds (front-rescored.json; empty if none).
  std::vector<double> rescored;
  bool rescored_feasible = false;
};

Status read_pareto_csv(const std::filesystem::path& path, int objectives,
                       std::vector<FrontMember>& out);

/// Summary keys of the best-Obj1 and best-Obj2 front members for a task: "fastest" and
/// "most_stable" for the walk and walk-omni, "least_sway" and "longest_kick" for the kick (Obj2 =
/// 1/distance), "best_obj1" and "best_obj2" otherwise.
struct RunPickNames {
  const char* best_obj1;
  const char* best_obj2;
};
RunPickNames run_pick_names(const std::string& task);

/// The non-dominated points of `points` (minimisation, 2 objectives), sorted by Obj1.
std::vector<std::vector<double>> non_dominated(std::vector<std::vector<double>> points);
/// Index of the knee point of a front: the member closest to the ideal point after scaling
/// each objective to [0, 1] over the front.
std::size_t knee_index(const std::vector<std::vector<double>>& front);

}  // namespace stride::opt
