// Run reports: what a robot optimisation run directory yields after (or during) the run.
//   front/NNN.json            one parameter file per pareto.csv row (the genes by parameter name),
//                             loadable by `stride-fw --params` and `stride sim walk --params`
//   pareto_by_generation.svg  the non-dominated feasible evaluations so far, after selected
//                             generations (like the seed's figures), Ind_O and the picks marked
//   hypervolume.svg           hypervolume against evaluations
// (both drawn by report/run_plots.hpp, write_plots; report.html by report/report_page.hpp)
// and a summary: the best-Obj1 and best-Obj2 members (walk: the fastest and the most stable;
// kick: the least sway and the longest kick) and the knee point (closest to the ideal point
// after normalising the front) beside Ind_O.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/optimiser/report/pareto_front.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"

namespace stride::opt {

/// Replaces front/ with one parameter file per pareto.csv row.
Status write_front_files(const std::filesystem::path& dir, const RobotTask& task);

/// Summary JSON: task, evaluations, front_size, ind_o, the two run_pick_names() members and
/// "knee" (each with objectives and front file name), warnings (what is missing or damaged in
/// the directory). Only a missing or unreadable run.json is an error.
Status summarise_run(const std::filesystem::path& dir, nlohmann::json& out);

}  // namespace stride::opt
