// The run's charts: the Pareto front by generation (the seed's Figs 6.5, 7.2, D.1) and the
// hypervolume against evaluations, as SVG for the files beside a run and for report.html.
//
// Front by generation: the non-dominated feasible evaluations made up to each of up to seven
// generations from the first to the last (if none is feasible yet, the best infeasible ones,
// said in the title). Every shown generation stays visible where fronts share points: earlier
// generations are drawn first with larger rings, later ones on top with smaller dots. Ind_O
// and the picks are marked and named; every point's tooltip gives its objectives, its
// evaluation and generation, and its front file when it is a member of the final front.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "stride/optimiser/report/run_data.hpp"

namespace stride::opt::report {

/// The generations shown in the front chart: 1, ..., last (at most `count`).
std::vector<int> shown_generations(int last_generation, int count = 7);

/// The colour of an individual in every chart and replay: 0 is Ind_O, 1.. the picks.
const char* individual_colour(std::size_t index);

std::string pareto_chart_svg(const RunData& data, const std::vector<RunPick>& picks);
std::string hypervolume_chart_svg(const RunData& data);

}  // namespace stride::opt::report

namespace stride::opt {

/// Writes both SVG plots from evaluations.jsonl and generations.jsonl.
Status write_plots(const std::filesystem::path& dir);

}  // namespace stride::opt
