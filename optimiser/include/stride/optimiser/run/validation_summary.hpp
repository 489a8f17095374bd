// The summary of a validation (validation.hpp): per individual and world the reached fraction,
// falls, median objectives, the gate and the gain kept; the flat table that `stride report`
// and `stride validate` show; the task's own figures (TaskType::validation_figures: walk-omni's
// and walk-ramp's speed per direction). Pure functions of the
// episodes' scores (no simulation here).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/optimiser/run/validation.hpp"

namespace stride::opt {

/// One validation episode: its score, or why its world could not be built.
struct EpisodeOutcome {
  EpisodeScore score;
  std::string setup_error;  ///< non-empty: the world was not built (the score is empty)
};

/// True when the episode reached the task's goal without a fall (validation.hpp).
bool validation_reached(const TaskConfig& config, const EpisodeScore& score);
/// Index of the objective the gate measures (walk, walk-omni: 0; kick: 1, 1/distance).
int gate_objective(const TaskConfig& config);
/// The median of `values` (the mean of the two middle ones for an even count; NaN if empty).
double median(std::vector<double> values);

/// The validation.json object. outcomes[individual][world][seed].
nlohmann::json summarise_validation(
    const std::filesystem::path& dir, const TaskConfig& config,
    const std::vector<ValidationIndividual>& individuals,
    const std::vector<ValidationWorld>& worlds,
    const std::vector<std::vector<std::vector<EpisodeOutcome>>>& outcomes);

}  // namespace stride::opt
