// report.html of a robot run directory (`stride report DIR`) and the one-episode page of
// `stride sim --html FILE`.
//
// The run report re-runs Ind_O and each pick (run_picks) deterministically: RobotTask::
// run_trial, trial 0, the very world, seed and noise settings of the run's first trial (from
// the task config in run.json), with an EpisodeCapturer watching; nothing is taken from the
// optimisation's own episodes. For a single-trial task the re-run scores exactly what the log
// says (the picks table shows both). The replays and pose strips draw that world's robot (the
// task's model: the config world's URDF, else igus) and its ground. Sections, in order:
// settings, picks (Ind_O against the picks, changes in %), validation (only when
// validation.json exists), front by generation, hypervolume, accelerometer, poses (strips at
// regular times, 9 frames 0.25 s apart: walk from 4 s, kick from 1.5 s before the ball first
// moves), replay, parameters (Table E).
// A run directory with missing pieces gives a page that says what is missing in each section
// and in the warnings list at the top.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/optimiser/report/html_replay.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"

namespace stride::opt::report {

struct ReportOutcome {
  std::filesystem::path file;
  std::size_t bytes = 0;
  std::vector<std::string> warnings;  ///< what is missing or failed, one line each
};

/// Writes DIR/report.html (atomically). Fails only when run.json cannot be read or the file
/// cannot be written; everything else becomes a warning and a note on the page. Warnings
/// already in `out` (the caller's) are kept and shown first.
Status write_report_html(const std::filesystem::path& dir, const RobotTask& task,
                         ReportOutcome& out);

/// One episode's page (`stride sim --html`): `facts` (name, value) as its summary table, the
/// accelerometer, a pose strip and the replay (2D and 3D). What the 3D view is missing
/// (three.js, a drawable model, the trajectory) is said on the page and appended to `warnings`.
Status write_episode_html(const std::filesystem::path& file, const std::string& title,
                          const std::vector<std::pair<std::string, std::string>>& facts,
                          const sim::RobotModel& model, const ReplayIndividual& episode,
                          const ReplayScene& scene, const std::vector<double>& strip_times_s,
                          std::vector<std::string>* warnings = nullptr);

}  // namespace stride::opt::report
