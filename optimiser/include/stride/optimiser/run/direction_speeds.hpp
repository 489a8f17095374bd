// Per-direction speed table of the omnidirectional walk (issue 22): for a walk-omni run, the
// speed along each commanded direction (forward, backward, left, right, turn left, turn right)
// of Ind_O, the picks (fastest overall, most stable, knee) and each direction's best front
// member, beside the reference figures of this robot class. `stride report` prints it; the
// table is built from genomes and a RobotTask alone, so a re-scoring command (validate on the
// other engine or fresh seeds) can fill it from its own task.
//
// Speeds are re-measured by simulation: the task's walk-omni episode in each of its trials
// (the worlds the run was scored in), averaged over the trials (the speed objective's mean).
//
// Reference: the Hamburg Bit-Bots' walk tuned for maximum speed per direction on NUgus (an
// igus-derived robot) in simulation: 0.38 m/s forward, 0.42 m/s backward, 0.26 m/s sideways,
// 1.97 rad/s turning (1,000 trials, 8-24 h on a 12-core machine; issue 22), kept once in
// walk_measures.hpp (kReferenceSpeeds).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/optimiser/nsga2/genome.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"

namespace stride::opt {

/// One row of the table.
struct DirectionSpeeds {
  std::string label;                          ///< "Ind_O", "fastest", "Bit-Bots NUgus (sim)", ...
  std::string file;                           ///< front file of the member, if any
  std::array<double, kOmniSegments> speed{};  ///< m/s (translations), rad/s (turns)
  std::array<std::string, kOmniSegments> source{};  ///< per cell, for "best" rows: the member
  int falls = 0;                                    ///< trials in which the robot fell
  int trials = 0;                                   ///< 0 for reference rows (not simulated)
};

/// The reference figures (Bit-Bots, NUgus in simulation).
DirectionSpeeds reference_direction_speeds();

/// Simulates `genome` in every trial of `task` (a walk-omni task) and averages the speeds.
Status measure_direction_speeds(const RobotTask& task, const Genome& genome,
                                const std::string& label, DirectionSpeeds& out);

/// For each direction, the fastest of `rows` (its label recorded in `source`).
DirectionSpeeds best_per_direction(const std::vector<DirectionSpeeds>& rows,
                                   const std::string& label);

/// The table as text: one row per entry, one column per direction.
std::string direction_table_text(const std::vector<DirectionSpeeds>& rows);
/// The table as JSON: [{label, file, falls, trials, speeds: {forward: .., ...}, source?}].
nlohmann::json direction_table_json(const std::vector<DirectionSpeeds>& rows);

/// The whole table of a walk-omni run directory: Ind_O, the picks named in `summary`
/// (summarise_run()), each direction's best front member, and the reference.
Status run_direction_table(const std::filesystem::path& dir, const RobotTask& task,
                           const nlohmann::json& summary, std::vector<DirectionSpeeds>& rows);

}  // namespace stride::opt
