// Run reports: what a robot optimisation run directory yields after (or during) the run.
//   front/NNN.json            one parameter file per pareto.csv row (the genes by parameter name),
//                             loadable by `stride-fw --params` and `stride sim walk --params`
//   pareto_by_generation.svg  the non-dominated feasible evaluations so far, after selected
//                             generations (like the seed's figures), Ind_O and the picks marked
//   hypervolume.svg           hypervolume against evaluations
// (both drawn by report/run_plots.hpp; report.html by report/report_page.hpp)
// and a summary: the best-Obj1 and best-Obj2 members (walk: the fastest and the most stable;
// kick: the least sway and the longest kick) and the knee point (closest to the ideal point
// after normalising the front) beside Ind_O.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/hal/status.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"

namespace stride::opt {

/// One row of pareto.csv.
struct FrontMember {
  std::vector<double> objectives;
  std::vector<double> genes;
};

Status read_pareto_csv(const std::filesystem::path& path, int objectives,
                       std::vector<FrontMember>& out);
/// Replaces front/ with one parameter file per pareto.csv row.
Status write_front_files(const std::filesystem::path& dir, const RobotTask& task);
/// Writes both SVG plots from evaluations.jsonl and generations.jsonl.
Status write_plots(const std::filesystem::path& dir);
/// Summary keys of the best-Obj1 and best-Obj2 front members for a task: "fastest" and
/// "most_stable" for the walk and walk-omni, "least_sway" and "longest_kick" for the kick (Obj2 =
/// 1/distance), "best_obj1" and "best_obj2" otherwise.
struct RunPickNames {
  const char* best_obj1;
  const char* best_obj2;
};
RunPickNames run_pick_names(const std::string& task);

/// Summary JSON: task, evaluations, front_size, ind_o, the two run_pick_names() members and
/// "knee" (each with objectives and front file name), warnings (what is missing or damaged in
/// the directory). Only a missing or unreadable run.json is an error.
Status summarise_run(const std::filesystem::path& dir, nlohmann::json& out);

/// The non-dominated points of `points` (minimisation, 2 objectives), sorted by Obj1.
std::vector<std::vector<double>> non_dominated(std::vector<std::vector<double>> points);
/// Index of the knee point of a front: the member closest to the ideal point after scaling
/// each objective to [0, 1] over the front.
std::size_t knee_index(const std::vector<std::vector<double>>& front);

}  // namespace stride::opt
