// report.html of a run directory and the one-episode page of `stride sim --html`.
#include "stride/optimiser/report/report_page.hpp"
#include "stride/optimiser/tasks/task_type.hpp"

#include <algorithm>
#include <thread>

#include "stride/core/atomic_file.hpp"
#include "stride/optimiser/report/html_page.hpp"
#include "stride/optimiser/report/html_replay3d.hpp"
#include "stride/optimiser/report/html_tables.hpp"
#include "stride/optimiser/report/run_plots.hpp"

namespace stride::opt::report {

namespace fs = std::filesystem;

namespace {

struct Rerun {
  Genome genome;
  EpisodeScore score;
  sim::EpisodeCapturer capturer;
  Status status;
  ReplayIndividual replay;
};

std::string outcome_note(const TaskConfig& config, const EpisodeScore& s, double end_s) {
  const TaskType* type = find_task_type(config.task);
  return type != nullptr ? type->outcome_note(config, s, end_s) : "";
}

double end_of(const ReplayIndividual& r) {
  return r.capture.frames.empty() ? 0.0 : r.capture.frames.back().time_s;
}

}  // namespace

Status write_report_html(const fs::path& dir, const RobotTask& task, ReportOutcome& out) {
  RunData data;
  if (Status s = load_run_data(dir, data); !s) return s;
  std::vector<std::string> earlier = std::move(out.warnings);
  out = {};
  out.warnings = std::move(earlier);
  out.warnings.insert(out.warnings.end(), data.warnings.begin(), data.warnings.end());
  const std::vector<RunPick> picks = run_picks(data);
  const TaskConfig& config = task.config();

  // Re-run Ind_O and the picks in the run's first-trial world (two at a time).
  std::vector<Rerun> runs(1 + picks.size());
  runs[0].genome = task.start_genome();
  runs[0].replay.name = "Ind_O";
  for (std::size_t i = 0; i < picks.size(); ++i) {
    runs[i + 1].genome.reals = picks[i].genes;
    runs[i + 1].replay.name = picks[i].label;
  }
  for (std::size_t i = 0; i < runs.size(); i += 2) {
    std::vector<std::thread> workers;
    for (std::size_t k = i; k < std::min(i + 2, runs.size()); ++k)
      workers.emplace_back(
          [&task, &r = runs[k]] { r.status = task.run_trial(r.genome, 0, r.score, &r.capturer); });
    for (auto& w : workers) w.join();
  }
  std::vector<ReplayIndividual> replays;
  std::vector<PickRow> rows;
  const nlohmann::json* ind_o = find_ind_o(data);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    Rerun& r = runs[i];
    r.replay.colour = individual_colour(i);
    PickRow row{r.replay.name, r.replay.colour, i == 0 ? "" : picks[i - 1].file, {}, {}, ""};
    if (i == 0 && ind_o != nullptr) row.objectives = objectives_of(*ind_o);
    if (i > 0) row.objectives = picks[i - 1].objectives;
    if (!r.status) {
      row.outcome = "re-run failed: " + r.status.message();
      out.warnings.push_back(r.replay.name + ": re-run failed: " + r.status.message());
    } else {
      r.replay.capture = r.capturer.finish();
      r.replay.note = outcome_note(config, r.score, end_of(r.replay));
      row.outcome = r.replay.note;
      if (config.world_count() == 1) row.rerun = r.score.objectives;
      replays.push_back(r.replay);
    }
    if (i == 0 && ind_o == nullptr && !data.evaluations.empty())
      out.warnings.push_back("Ind_O (the start genome) is not among the logged evaluations");
    rows.push_back(std::move(row));
  }

  // The run's own robot and ground: the world the re-runs above ran in (trial 0).
  const sim::WorldOptions world = task.world_options(0);
  sim::RobotModel loaded;  // the task loads it when it is made; if that failed, again here
  if (task.robot_model() == nullptr)
    if (Status s = sim::RobotModel::load_file(world.urdf, loaded); !s)
      out.warnings.push_back("robot model: " + s.message());
  const sim::RobotModel& model = task.robot_model() != nullptr ? *task.robot_model() : loaded;
  ReplayScene scene = replay_scene(world);
  const TaskType* type = find_task_type(config.task);
  const bool ball = type != nullptr && type->descriptor().uses_ball;
  if (type != nullptr) scene.goal_m = type->replay_goal_m(config);
  double end = 0.0;
  for (const auto& r : replays) end = std::max(end, end_of(r));
  const double action_s = type != nullptr ? type->action_at_s(config) : 0.0;  // the kick
  const std::vector<double> times =
      ball ? strip_times(std::max(action_s, first_ball_motion_s(replays, action_s + 1.0) - 1.5),
                         0.25, 9, end)
           : strip_times(std::min(4.0, end / 3), 0.25, 9, end);

  HtmlPage page("Stride run report: " + (data.task.empty() ? std::string("run") : data.task),
                dir.string() + " - " +
                    run_progress_text(data.generations_done, data.generations_planned) + ", " +
                    std::to_string(data.evaluations.size()) + " evaluations, " +
                    std::to_string(data.front.size()) + " front members");
  page.add_warnings(out.warnings);
  page.add_section("settings", "Settings", settings_table_html(data));
  page.add_section("picks", "Ind_O and the picks", picks_table_html(data, rows));
  const std::string validation = validation_table_html(dir / "validation.json");
  if (!validation.empty())
    page.add_section("validation", "Validation (validation.json)", validation);
  page.add_section("pareto", "Pareto front by generation",
                   (data.evaluations.empty() ? missing_note("No evaluations logged yet.") : "") +
                       pareto_chart_svg(data, picks));
  page.add_section("hypervolume", "Hypervolume",
                   (data.generations.empty() ? missing_note("No generations logged yet.") : "") +
                       hypervolume_chart_svg(data));
  const std::string note = "<p class=\"note\">Re-run in the run's world (trial 0: seed " +
                           std::to_string(config.trial_seed) +
                           (config.trials > 1 ? ", randomised" : ", nominal") +
                           "), not replayed from the optimisation's episodes.</p>\n";
  page.add_section("accelerometer", "Accelerometer over time",
                   note + accel_charts_html(replays, std::pair(times.front(), times.back())));
  std::string strips = model.links().empty() ? missing_note("The robot model could not be loaded.")
                                             : pose_strips_html(model, replays, times, scene, true);
  page.add_section("poses", "Poses at regular times", strips);
  if (!replays.empty() && !model.links().empty()) {
    std::vector<std::string> replay_warnings;
    add_replay_section(page, note, model, replays, scene, replay_warnings);
    out.warnings.insert(out.warnings.end(), replay_warnings.begin(), replay_warnings.end());
    page.add_warnings(replay_warnings);
  } else {
    page.add_section("replay", "Replay",
                     missing_note(replays.empty() ? "No episode could be re-run: no trajectory to "
                                                    "replay (2D or 3D)."
                                                  : "The robot model could not be loaded: "
                                                    "nothing to replay."));
  }
  page.add_section("parameters", "Parameters that moved most (Table E)",
                   parameter_table_html(data, picks));
  const std::string html = page.str();
  out.file = dir / "report.html";
  out.bytes = html.size();
  return core::write_file_atomically(out.file, html);
}

Status write_episode_html(const fs::path& file, const std::string& title,
                          const std::vector<std::pair<std::string, std::string>>& facts,
                          const sim::RobotModel& model, const ReplayIndividual& episode,
                          const ReplayScene& scene, const std::vector<double>& strip_times_s,
                          std::vector<std::string>* warnings) {
  HtmlPage page(title, episode.note);
  std::string table = "<table id=\"episode-table\">";
  for (const auto& [k, v] : facts)
    table += "<tr><th class=\"name\">" + html_escape(k) + "</th><td class=\"name\">" +
             html_escape(v) + "</td></tr>";
  page.add_section("episode", "Episode", table + "</table>\n");
  page.add_section(
      "accelerometer", "Accelerometer over time",
      accel_charts_html(
          {episode}, strip_times_s.empty()
                         ? std::nullopt
                         : std::optional(std::pair(strip_times_s.front(), strip_times_s.back()))));
  page.add_section("poses", "Poses at regular times",
                   pose_strips_html(model, {episode}, strip_times_s, scene, false));
  std::vector<std::string> replay_warnings;
  add_replay_section(page, "", model, {episode}, scene, replay_warnings);
  page.add_warnings(replay_warnings);
  if (warnings != nullptr)
    warnings->insert(warnings->end(), replay_warnings.begin(), replay_warnings.end());
  return core::write_file_atomically(file, page.str());
}

}  // namespace stride::opt::report
