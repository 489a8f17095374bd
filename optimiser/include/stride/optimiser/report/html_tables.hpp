// The tables of report.html: the run's settings, Ind_O against the picks, the validation
// results (validation.json, read tolerantly) and the parameters that moved most against Ind_O
// (the seed's Table E).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/optimiser/report/run_data.hpp"

namespace stride::opt::report {

/// Settings from run.json: task, seed, population, generations, operators, episode, trials.
std::string settings_table_html(const RunData& data);

/// One row of the picks table: logged objectives and, when the individual was re-run for the
/// replay, what the re-run scored (they agree for a single-trial task: the run is
/// deterministic).
struct PickRow {
  std::string name;
  std::string colour;
  std::string file;                          ///< "" for Ind_O
  std::vector<double> objectives;            ///< as logged
  std::optional<std::vector<double>> rerun;  ///< the replay episode's objectives
  std::string outcome;                       ///< how the replay episode ended
};
/// Ind_O (rows[0]) against the picks, with each objective's change against Ind_O in %.
std::string picks_table_html(const RunData& data, const std::vector<PickRow>& rows);

/// validation.json as a table. Its format belongs to `stride validate`; this reader takes any
/// JSON: every object with at least one number among its values becomes a row, labelled by its
/// path (e.g. "knee / mujoco"), with a column per scalar field. Returns "" if there is no
/// file; a note if it cannot be parsed.
std::string validation_table_html(const std::filesystem::path& file);

/// The genes that moved most against Ind_O (largest change in % of the gene's range over the
/// picks), `top` of them, then every gene in a collapsed <details>.
std::string parameter_table_html(const RunData& data, const std::vector<RunPick>& picks,
                                 std::size_t top = 15);

}  // namespace stride::opt::report
