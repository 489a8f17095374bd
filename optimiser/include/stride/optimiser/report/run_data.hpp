// RunData: what a robot run directory holds, read tolerantly for reports. Only run.json is
// required; a missing or empty evaluations.jsonl, generations.jsonl or pareto.csv, a
// truncated or damaged log line or a missing front file becomes one line in `warnings`
// (the report shows them and `stride report` prints them), never an error.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/optimiser/report/pareto_front.hpp"

namespace stride::opt::report {

struct RunData {
  std::filesystem::path dir;
  nlohmann::json run = nlohmann::json::object();  ///< run.json
  std::string task;                               ///< run.json "problem"
  std::vector<nlohmann::json> evaluations;        ///< the readable lines of evaluations.jsonl
  std::vector<nlohmann::json> generations;        ///< the readable lines of generations.jsonl
  std::vector<FrontMember> front;                 ///< pareto.csv rows (front/NNN.json = row NNN)
  std::vector<std::string> warnings;              ///< what is missing or damaged, one line each
  std::size_t generations_done = 0;               ///< the last generation in generations.jsonl
  std::size_t generations_planned = 0;  ///< run.json settings.generations (0: not recorded)
  /// True while the run has logged fewer generations than it plans (stopped or still running).
  bool unfinished() const { return generations_planned > generations_done; }
};

/// "generation 8 of 50 (unfinished)" while done < planned, else "50 generations".
std::string run_progress_text(std::size_t done, std::size_t planned);

/// Reads a run directory. Fails only when run.json is missing or not a JSON object.
Status load_run_data(const std::filesystem::path& dir, RunData& out);

/// True for an evaluation that did not fail, has objectives and no constraint violation.
bool feasible(const nlohmann::json& evaluation);
/// The objectives of an evaluation ({} if it has none that are numbers).
std::vector<double> objectives_of(const nlohmann::json& evaluation);

/// Ind_O's evaluation: the generation-1 evaluation whose genes are run.json's start genome.
const nlohmann::json* find_ind_o(const RunData& data);
/// run.json's start genome (Ind_O), empty if absent.
std::vector<double> start_genes(const RunData& data);

/// A chosen front member. Members picked for several reasons appear once, `label` naming
/// every reason ("fastest, knee").
struct RunPick {
  std::vector<std::string> keys;   ///< summary keys: run_pick_names() and "knee"
  std::string label;               ///< e.g. "fastest, knee"
  std::size_t front_index = 0;     ///< pareto.csv row
  std::string file;                ///< "front/NNN.json"
  std::vector<double> objectives;  ///< the run's (pareto.csv)
  std::vector<double> genes;
  std::vector<double> rescored;  ///< on fresh worlds (front-rescored.json), if the run has them
};
/// The best member for each objective and the knee point of the front, without duplicates.
/// A resampling run's picks come from its rescored front: the rows feasible on the fresh
/// worlds, non-dominated there, picked by their fresh scores.
std::vector<RunPick> run_picks(const RunData& data);

/// The front file name of pareto.csv row `index`: "front/NNN.json".
std::string front_file_name(std::size_t index);

}  // namespace stride::opt::report

namespace stride::opt::report {

/// Axis names of the two objectives of a task (walk: time to the goal, max |a|; kick: sway,
/// 1 / ball distance; otherwise f1, f2).
struct ObjectiveNames {
  std::string f1, f2;
};
ObjectiveNames objective_names(const RunData& data);

}  // namespace stride::opt::report
