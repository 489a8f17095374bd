// `stride report DIR`: rebuilds the plots and front/ files of a robot optimisation run, writes
// report.html (report_page.hpp) and prints the best member for each objective (walk: fastest,
// most stable; kick: least sway, longest kick) and the knee point beside Ind_O; for a
// walk-omni run also the per-direction speed table (direction_speeds.hpp), re-simulated in the
// run's worlds.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "stride/core/cli_args.hpp"
#include "stride/core/json_file.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/optimiser/report/report_page.hpp"
#include "stride/optimiser/report/run_data.hpp"
#include "stride/optimiser/report/run_plots.hpp"
#include "stride/optimiser/run/direction_speeds.hpp"
#include "stride/optimiser/run/optimisation_run.hpp"
#include "stride/optimiser/run/run_report.hpp"
#include "stride/optimiser/run/validation.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"

namespace {

using stride::Status;

const stride::tools::CommandErrors errors("report");

void print_member(const std::string& label, const nlohmann::json& m, const nlohmann::json& ind_o,
                  bool kick) {
  if (m.is_null()) return;
  const auto f = m["objectives"].get<std::vector<double>>();
  std::printf("%-13s f1 %10.4g  f2 %10.4g", label.c_str(), f[0], f[1]);
  if (kick && f[1] > 0) std::printf("  (ball %.2f m)", 1.0 / f[1]);
  if (ind_o.is_object()) {
    const auto o = ind_o["objectives"].get<std::vector<double>>();
    if (o[0] > 0 && o[1] > 0 && o[0] < 1e29)
      std::printf("  (%+.1f %%, %+.1f %% vs Ind_O)", 100.0 * (f[0] - o[0]) / o[0],
                  100.0 * (f[1] - o[1]) / o[1]);
  }
  if (m.contains("file")) std::printf("  %s", m["file"].get<std::string>().c_str());
  std::printf("\n");
}

void print_help(const stride::core::CliArgs& args) {
  std::printf(
      "usage: stride report DIR [--json]\nRebuilds DIR/pareto_by_generation.svg, "
      "DIR/hypervolume.svg and DIR/front/, writes DIR/report.html\n"
      "(one self-contained page: settings, picks, fronts, accelerometer, poses, replay of\n"
      "Ind_O and the picks re-run in the run's world, parameter changes),\n"
      "then prints the best member for each objective (walk: fastest, most stable;\n"
      "kick: least sway, longest kick) and the knee point beside Ind_O.\n"
      "A walk-omni run also gets a table of the speed per direction of Ind_O, the\n"
      "picks and each direction's best front member (simulated again in the run's\n"
      "worlds) beside the reference figures (Bit-Bots, NUgus in simulation).\n"
      "With DIR/validation.json (stride validate) also the validation table and the\n"
      "same in words (where each individual holds, why it fails elsewhere).\n\n%s",
      args.help().c_str());
}

/// DIR's run.json: a robot task's run (its type and task config); errors are bad input.
Status read_run(const std::filesystem::path& dir, stride::opt::RunConfig& config,
                const stride::opt::TaskType*& type, stride::opt::TaskConfig& task) {
  if (!std::filesystem::exists(dir / "run.json"))
    return Status::error((dir / "run.json").string() + " does not exist");
  if (auto st = stride::opt::read_run_config(dir, config); !st) return st;
  type = stride::opt::find_task_type(config.problem);
  if (type == nullptr)
    return Status::error(dir.string() + " is a '" + config.problem + "' run, not a " +
                         stride::opt::task_type_list() + " task");
  if (auto st = stride::opt::parse_task_record(config.task, task); !st)
    return Status::error("run.json task: " + st.message());
  return {};
}

/// validation.json (stride validate): its object when present and readable, else null (with a
/// warning if it is there but not a JSON object).
nlohmann::json read_validation(const std::filesystem::path& dir) {
  nlohmann::json validation = nullptr;
  stride::core::JsonFileError why = stride::core::JsonFileError::kNone;
  const bool read = stride::core::read_json_file(dir / "validation.json", validation, &why).is_ok();
  if ((read && !validation.is_object()) || why == stride::core::JsonFileError::kNotJson) {
    errors.warning((dir / "validation.json").string() + " is not a JSON object");
    validation = nullptr;
  }
  return validation;
}

/// The text summary: the run, Ind_O and the picks, the direction and validation tables, the
/// files written.
void print_summary(const std::filesystem::path& dir, const stride::opt::RunConfig& config,
                   const stride::opt::TaskType& type, const nlohmann::json& summary,
                   const std::vector<stride::opt::DirectionSpeeds>& directions,
                   const nlohmann::json& validation,
                   const stride::opt::report::ReportOutcome& page) {
  const std::string progress = stride::opt::report::run_progress_text(
      summary["generations"].get<std::size_t>(), summary["generations_planned"].get<std::size_t>());
  std::printf("%s run, %s, %zu evaluations, %zu front members (objectives: %s)\n",
              config.problem.c_str(), progress.c_str(), summary["evaluations"].get<std::size_t>(),
              summary["front_size"].get<std::size_t>(), type.descriptor().legend.c_str());
  const bool kick = type.descriptor().uses_ball;
  const nlohmann::json& o = summary["ind_o"];
  if (o.is_object()) print_member("Ind_O", o, nullptr, kick);
  const stride::opt::RunPickNames names = stride::opt::run_pick_names(config.problem);
  for (const std::string key : {names.best_obj1, names.best_obj2, "knee"}) {
    std::string label = key;
    std::replace(label.begin(), label.end(), '_', ' ');
    if (summary.contains(key)) print_member(label, summary[key], o, kick);
  }
  if (!directions.empty())
    std::printf("\n%s", stride::opt::direction_table_text(directions).c_str());
  if (stride::opt::is_validation_file(validation))
    std::printf("\n%s", stride::opt::validation_text(validation).c_str());
  else if (validation.is_null())
    std::printf("\nno validation.json (stride validate %s)\n", dir.c_str());
  std::printf("plots: %s, %s\nreport: %s (%.1f MB; open it in a browser)\n",
              (dir / "pareto_by_generation.svg").c_str(), (dir / "hypervolume.svg").c_str(),
              page.file.c_str(), static_cast<double>(page.bytes) / 1e6);
}

}  // namespace

int run_report(int argc, char** argv) {
  stride::core::CliArgs args;
  args.option("json", "print the summary as one JSON object", false)
      .option("help", "show this help", false);
  if (auto st = args.parse(argc, argv); !st) return errors.bad_input(st.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  if (args.positional().size() != 1) return errors.bad_input("expected one run directory");
  const std::filesystem::path dir = args.positional()[0];
  stride::opt::RunConfig config;
  const stride::opt::TaskType* type = nullptr;
  stride::opt::TaskConfig task;
  if (auto st = read_run(dir, config, type, task); !st) return errors.bad_input(st.message());
  const stride::opt::RobotTask robot_task(task);
  // What is missing is said once, on one line, and on the page; only an unreadable run.json
  // or an unwritable file stops the report.
  stride::opt::report::RunData before;
  if (auto st = stride::opt::report::load_run_data(dir, before); !st)
    return errors.bad_input(st.message());
  stride::opt::report::ReportOutcome page;
  if (!before.front.empty()) {
    for (const std::string& w : before.warnings)
      if (w.rfind("front/", 0) == 0) page.warnings.push_back(w + "; rewritten from pareto.csv");
    if (auto st = stride::opt::write_front_files(dir, robot_task); !st)
      return errors.failure(st.message());
  }
  if (auto st = stride::opt::write_plots(dir); !st) return errors.failure(st.message());
  nlohmann::json summary;
  if (auto st = stride::opt::summarise_run(dir, summary); !st) return errors.failure(st.message());
  if (auto st = stride::opt::report::write_report_html(dir, robot_task, page); !st)
    return errors.failure(st.message());
  summary["warnings"] = page.warnings;
  summary["plots"] = {(dir / "pareto_by_generation.svg").string(),
                      (dir / "hypervolume.svg").string()};
  summary["report"] = page.file.string();
  summary["report_bytes"] = page.bytes;
  if (!page.warnings.empty()) {
    std::string line;
    for (const auto& w : page.warnings) line += (line.empty() ? "" : "; ") + w;
    errors.warning(line + " (see " + page.file.string() + ")");
  }
  std::vector<stride::opt::DirectionSpeeds> directions;
  if (type->descriptor().measures_directions) {
    if (auto st = stride::opt::run_direction_table(dir, robot_task, summary, directions); !st)
      return errors.failure(st.message());
    summary["directions"] = stride::opt::direction_table_json(directions);
  }
  const nlohmann::json validation = read_validation(dir);
  if (validation.is_object()) summary["validation"] = validation;
  if (args.has("json")) {
    std::printf("%s\n", summary.dump().c_str());
    return 0;
  }
  print_summary(dir, config, *type, summary, directions, validation, page);
  return 0;
}

STRIDE_COMMAND(report, "plots and summary of an optimisation run directory", run_report);
