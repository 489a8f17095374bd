// `stride calibrate LOG... --fit NAME[,NAME...] --out WORLD.json`: fits the simulated robot to
// flight logs (calibration.hpp) and writes a world file (world_file.hpp) that --world and task
// configs accept. Progress on stderr; Ctrl-C stops after the running evaluation and keeps the
// progress file, which --resume continues from. Bad input: one line, exit 2, no output file.
// Before fitting two or more values it measures their identifiability on the logs
// (identifiability.hpp) and refuses a set two of whose estimates correlate beyond
// --max-correlation; --identifiability prints that analysis and fits nothing.
#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "calibration_check.hpp"
#include "stride/calibration/calibration.hpp"
#include "stride/calibration/identifiability.hpp"
#include "stride/core/atomic_file.hpp"
#include "stride/core/cli_args.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/sim_hal/sim_cli.hpp"

namespace {

using stride::Status;
namespace sim = stride::sim;
namespace calibration = stride::calibration;
namespace fw = stride::fw;
namespace core = stride::core;

std::atomic<bool> g_stop{false};
extern "C" void on_sigint(int) {
  g_stop.store(true);
}

const stride::tools::CommandErrors errors("calibrate");

void declare_options(core::CliArgs& args) {
  args.option("help", "show this help", false);
  args.option("fit", "parameters to fit, comma-separated (see below)", true);
  args.option("out", "the world file to write (required)", true);
  args.option("window", "replay window [s]", true, "15");
  args.option("robot-mass", "the robot's weighed mass [kg]: sets the trunk mass (not fitted)",
              true);
  args.option("jobs", "threads replaying windows side by side", true, "1");
  args.option("max-evals", "evaluations per fit of the continuous parameters", true, "250");
  args.option("subsets",
              "re-fits without one of K subsets of the windows, for the uncertainty "
              "(0: none)",
              true, "3");
  args.option("single-stage",
              "fit every value on every window at once (default: in stages, each on the windows "
              "that tell it best)",
              false);
  args.option("resume", "continue a stopped run from OUT.progress.jsonl", false);
  args.option("identifiability",
              "print the values' sensitivity per routine part, standard errors and correlations "
              "on the logs, and fit nothing (--out not needed)",
              false);
  args.option("no-check",
              "skip the prediction check after the fit (the default walk in the nominal and the "
              "calibrated world, about 20 s)",
              false);
  args.option("max-correlation",
              "refuse to fit two values whose estimates correlate beyond this (|r|)", true, "0.95");
  args.option("allow-confounded", "fit even values the logs cannot tell apart", false);
  args.option("servo-table", "the firmware's servo table (must be the logs')", true,
              fw::ServoTable::default_path().string());
  args.option("robot-description", "the firmware's rigid-body model (must be the logs')", true,
              fw::RobotDescription::default_path().string());
  sim::declare_world_options(args);
}

void print_help(const core::CliArgs& args) {
  std::string names;
  for (const calibration::CalibrationParameter& p : calibration::calibration_parameters()) {
    char line[160];
    const std::string mark = calibration::warning_mark(p);
    std::snprintf(line, sizeof line, "  %-14s %-32s [%g, %g] %s%s%s\n", p.name.c_str(),
                  p.what.c_str(), p.lower, p.upper, p.unit.c_str(), mark.empty() ? "" : "  ",
                  mark.c_str());
    names += line;
  }
  std::printf(
      "usage: stride calibrate LOG... --fit NAME[,NAME...] --out WORLD.json [world options]\n\n"
      "Fits the simulated robot to flight logs (stride-fw --record; the identification\n"
      "routine of firmware/scripts/IDENTIFICATION.md): minimises the replay error (stride\n"
      "replay) over every window of every log, prints each fitted value with an uncertainty\n"
      "from re-fits on subsets of the windows, and writes a world file for --world and task\n"
      "configs. The world options give the world the logs are replayed in (default: the\n"
      "faithful world, noise off); a world file there is the start of the fit.\n"
      "Two or more values are first checked for identifiability on the logs (sensitivity by\n"
      "finite differences, Fisher information with the sensor models' noise): a pair whose\n"
      "estimates correlate beyond --max-correlation is refused, naming what would separate\n"
      "them; --identifiability prints the analysis instead of fitting. On the routine's own\n"
      "logs no pair reaches the default 0.95, so that check rarely refuses. The warnings are\n"
      "another thing: a fixed table, the result of a study on drawn robots\n"
      "(tests/bench/RESULTS.md), not a finding on these logs; a value marked (warned) below\n"
      "is fitted with a line saying why it is often not found.\n\n"
      "Parameters (--fit; gyro_bias and accel_bias name three axes, all every one):\n%s\n%s",
      names.c_str(), args.help().c_str());
}

/// The logs, --out and --fit are required; --out must be a file in an existing folder.
Status read_out(const core::CliArgs& args, std::filesystem::path& out) {
  if (args.positional().empty()) return Status::error("expected at least one flight log");
  if (!args.has("fit")) return Status::error("--fit: name the parameters to fit");
  if (args.has("identifiability")) return {};
  if (!args.has("out")) return Status::error("--out: the world file to write is required");
  out = args.get("out");
  std::error_code error;
  if (out.has_parent_path() && !std::filesystem::is_directory(out.parent_path(), error))
    return Status::error("--out: no such folder '" + out.parent_path().string() + "'");
  if (std::filesystem::is_directory(out, error)) return Status::error("--out: is a folder");
  return {};
}

/// --fit, --window, --jobs, --max-evals and --subsets into the fit's options.
Status read_fit_options(const core::CliArgs& args, calibration::CalibrationOptions& options) {
  if (Status s = calibration::parse_fit_names(args.get("fit"), options.fit); !s) return s;
  if (Status s = args.get_double("window", options.replay.window_s); !s) return s;
  std::int64_t jobs = 1, max_evals = 250, subsets = 3;
  if (Status s = args.get_int("jobs", jobs); !s) return s;
  if (Status s = args.get_int("max-evals", max_evals); !s) return s;
  if (Status s = args.get_int("subsets", subsets); !s) return s;
  if (jobs < 1 || jobs > 256) return Status::error("--jobs: must be in 1..256");
  if (max_evals < 1 || max_evals > 100000)
    return Status::error("--max-evals: must be in 1..100000");
  if (subsets < 0 || subsets == 1 || subsets > 20)
    return Status::error("--subsets: must be 0 or in 2..20");
  options.replay.threads = static_cast<int>(jobs);
  options.max_evaluations = static_cast<int>(max_evals);
  options.subsets = static_cast<int>(subsets);
  options.staged = !args.has("single-stage");
  if (args.has("push"))
    return Status::error("--push: not available (the logged commands are replayed)");
  return {};
}

/// The replay world (noise off unless asked: the logged sensors carry the robot's noise) and
/// the fit's start: the world file given with --world (read once, with the world's other
/// options), else the named world's nominal robot.
Status read_world(const core::CliArgs& args, sim::WorldOptions& world, sim::WorldFile& start) {
  sim::WorldSpec spec;
  if (Status s = sim::read_world_spec(args, spec); !s) return s;
  if (args.get_all("noise").empty()) spec.noise = false;
  world = spec.to_options();
  start = spec.file.value_or(sim::WorldFile{});
  start.base = spec.base;
  return {};
}

/// Reads every log and checks that it replays on this firmware's servo table and robot
/// description with at least one window of `window_s`.
Status read_logs(const core::CliArgs& args, double window_s, std::vector<fw::FlightLog>& logs) {
  fw::ServoTable servos;
  if (Status s = fw::ServoTable::load(args.get("servo-table"), servos); !s)
    return Status::error("--servo-table: " + s.message());
  fw::RobotDescription robot;
  if (Status s = fw::RobotDescription::load(args.get("robot-description"), servos, robot); !s)
    return Status::error("--robot-description: " + s.message());
  logs.resize(args.positional().size());
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const std::string& path = args.positional()[i];
    if (Status s = fw::read_flight_log(path, logs[i]); !s) return s;
    if (Status s = sim::check_replayable(logs[i], servos, robot); !s)
      return Status::error(path + ": " + s.message());
    if (Status s = sim::check_window(logs[i], window_s); !s)
      return Status::error(path + ": " + s.message());
  }
  return {};
}

/// Measured, not fitted (calibration.hpp): the supply from the logs unless --fit voltage, the
/// trunk from --robot-mass.
Status set_measured_values(const core::CliArgs& args,
                           const calibration::CalibrationOptions& options,
                           const std::vector<const fw::FlightLog*>& logs,
                           const sim::WorldOptions& world, sim::WorldFile& start) {
  const auto fitted = [&options](const char* name) {
    return std::find(options.fit.begin(), options.fit.end(), name) != options.fit.end();
  };
  double volts = 0.0;
  if (!fitted("voltage") && calibration::logged_supply_voltage(logs, volts))
    start.supply_voltage_v = volts;
  if (args.has("robot-mass")) {
    if (fitted("trunk_mass"))
      return Status::error("--robot-mass: sets the trunk mass; do not also --fit trunk_mass");
    double kg = 0.0;
    if (Status s = args.get_double("robot-mass", kg); !s) return s;
    if (Status s = calibration::trunk_scale_for_mass(world, kg, start.robot.trunk_mass_scale); !s)
      return s;
  }
  return {};
}

/// OUT.progress.jsonl: absent for a new fit, present for --resume.
Status set_progress_file(const core::CliArgs& args, const std::filesystem::path& out,
                         calibration::CalibrationOptions& options) {
  std::error_code error;
  options.progress_file = out;
  options.progress_file += ".progress.jsonl";
  options.resume = args.has("resume");
  if (!options.resume && std::filesystem::exists(options.progress_file, error))
    return Status::error(options.progress_file.string() +
                         " exists: a stopped run (--resume continues it) or remove it");
  if (options.resume && !std::filesystem::exists(options.progress_file, error))
    return Status::error("--resume: no progress file " + options.progress_file.string());
  return {};
}

/// The identifiability of --fit's values on the logs: printed (--identifiability), or a
/// refusal naming the first confounded pair (two or more values, no --allow-confounded).
/// `done` is set when nothing is left to do.
Status check_identifiability(const core::CliArgs& args,
                             const calibration::CalibrationOptions& options,
                             const std::vector<const fw::FlightLog*>& logs,
                             const sim::WorldOptions& world, const sim::WorldFile& start,
                             bool& done) {
  const bool print = args.has("identifiability");
  done = print;
  double threshold = 0.95;
  if (Status s = args.get_double("max-correlation", threshold); !s) return s;
  if (!(threshold > 0.0 && threshold <= 1.0))
    return Status::error("--max-correlation: must be in (0, 1], got " +
                         args.get("max-correlation"));
  if (!print && (options.fit.size() < 2 || args.has("allow-confounded"))) return {};
  calibration::IdentifiabilityOptions analysis;
  analysis.names = options.fit;
  analysis.replay = options.replay;
  if (print)  // (a refusal is the only line on stderr)
    std::fprintf(stderr, "identifiability of %zu values (about %zu replays of the logs)\n",
                 options.fit.size(), 2 * options.fit.size() + 1);
  calibration::IdentifiabilityResult result;
  if (Status s = calibration::analyse_identifiability(logs, world, start, analysis, result); !s)
    return s;
  if (print) {
    std::printf("%s", calibration::identifiability_table(result).c_str());
    return {};
  }
  for (const calibration::ValueIdentifiability& v : result.values)
    if (v.total <= 0.0)
      return Status::error("--fit: " + v.name +
                           " does not change the replayed logs at all: leave it out (or "
                           "--allow-confounded)");
  const auto pairs = calibration::confounded_pairs(result, threshold);
  if (pairs.empty()) return {};
  char text[200];
  std::snprintf(text, sizeof text,
                "--fit: %s and %s cannot be told apart on these logs (correlation %+.3f, beyond "
                "%.2f): ",
                pairs[0].first.c_str(), pairs[0].second.c_str(), pairs[0].correlation, threshold);
  return Status::error(text + calibration::what_separates(pairs[0].first, pairs[0].second) +
                       "; or fit one of them (--allow-confounded fits both)");
}

/// Each fitted value with its start and uncertainty, then the objective and the errors.
void print_fit(const calibration::CalibrationResult& result, const std::filesystem::path& out) {
  std::printf("%-14s %10s %10s %12s  %s\n", "parameter", "start", "fitted", "uncertainty", "unit");
  for (const calibration::FittedValue& v : result.values) {
    std::string unit;
    for (const calibration::CalibrationParameter& p : calibration::calibration_parameters())
      if (p.name == v.name) unit = p.unit;
    std::printf("%-14s %10.4g %10.4g %12.3g  %s\n", v.name.c_str(), v.start, v.value, v.uncertainty,
                unit.c_str());
  }
  std::printf(
      "replay objective J: %.4g in the nominal world, %.4g at the start, %.4g fitted (%d "
      "replays, %d from the progress file)\n",
      result.nominal_objective, result.start_objective, result.objective, result.evaluations,
      result.stored_evaluations);
  std::printf("position RMS %.5f -> %.5f rad, load RMS %.4f -> %.4f; wrote %s\n",
              result.start_errors.position_all_rad, result.errors.position_all_rad,
              result.start_errors.load_all, result.errors.load_all, out.string().c_str());
}

/// The prediction check (calibration_check.hpp): the nominal and the calibrated world, with
/// the sensor noise the command line gives a simulation (on unless --noise off).
Status print_prediction_check(const core::CliArgs& args,
                              const std::vector<const fw::FlightLog*>& logs,
                              const sim::WorldOptions& world, const sim::ReplayOptions& replay,
                              const sim::WorldFile& calibrated) {
  sim::WorldOptions simulated = world;
  if (args.get_all("noise").empty()) simulated.imu.set_noise(true);
  sim::WorldFile nominal;
  nominal.base = calibrated.base;
  sim::WorldOptions nominal_world = simulated, calibrated_world = simulated;
  nominal.apply_calibration(nominal_world);
  calibrated.apply_calibration(calibrated_world);
  std::fprintf(stderr,
               "prediction check: the default walk in the nominal and the calibrated "
               "world\n");
  double logged_peak = 0.0;
  stride::tools::WorldPrediction n, c;
  if (Status s = stride::tools::predict(logs, nominal_world, replay, logged_peak, n); !s) return s;
  if (Status s = stride::tools::predict(logs, calibrated_world, replay, logged_peak, c); !s)
    return s;
  std::printf("%s", stride::tools::prediction_table(logged_peak, n, c).c_str());
  return {};
}

}  // namespace

int run_calibrate(int argc, char** argv) {
  core::CliArgs args;
  declare_options(args);
  if (Status s = args.parse(argc, argv); !s) return errors.bad_input(s.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  std::filesystem::path out;
  calibration::CalibrationOptions options;
  sim::WorldOptions world;
  sim::WorldFile start;
  std::vector<fw::FlightLog> logs;
  if (Status s = read_out(args, out); !s) return errors.bad_input(s.message());
  if (Status s = read_fit_options(args, options); !s) return errors.bad_input(s.message());
  if (Status s = read_world(args, world, start); !s) return errors.bad_input(s.message());
  if (Status s = read_logs(args, options.replay.window_s, logs); !s)
    return errors.bad_input(s.message());
  std::vector<const fw::FlightLog*> log_ptrs;
  std::size_t windows = 0;
  for (const fw::FlightLog& log : logs) {
    log_ptrs.push_back(&log);
    windows += sim::count_windows(log, options.replay.window_s);
  }
  if (!args.has("identifiability") && options.subsets > 0 &&
      windows < static_cast<std::size_t>(options.subsets))
    return errors.bad_input("--subsets: " + std::to_string(options.subsets) +
                            " subsets need at least " + std::to_string(options.subsets) +
                            " windows; the logs have " + std::to_string(windows) + " of " +
                            args.get("window") + " s");
  if (Status s = set_measured_values(args, options, log_ptrs, world, start); !s)
    return errors.bad_input(s.message());
  if (!args.has("identifiability"))
    if (Status s = set_progress_file(args, out, options); !s) return errors.bad_input(s.message());
  bool done = false;
  if (Status s = check_identifiability(args, options, log_ptrs, world, start, done); !s)
    return errors.bad_input(s.message());
  if (done) return 0;
  const bool fit_voltage =
      std::find(options.fit.begin(), options.fit.end(), "voltage") != options.fit.end();

  options.stop = &g_stop;
  std::signal(SIGINT, on_sigint);
  options.on_evaluation = [](const std::string& fit, int n, double j, double best) {
    std::fprintf(stderr, "\r%-9s evaluation %4d  J %10.4f  best %10.4f", fit.c_str(), n, j, best);
    std::fflush(stderr);
  };
  std::fprintf(stderr, "stride calibrate: %zu log(s), fitting %s in %s\n", logs.size(),
               args.get("fit").c_str(), sim::describe_world(world).c_str());
  const std::vector<std::string> warnings = calibration::fit_warnings(options.fit);
  for (const std::string& w : warnings) errors.warning(w);
  std::fprintf(stderr, "supply %.2f V (%s), trunk mass x%.4f (%s)\n", start.supply_voltage_v,
               fit_voltage ? "fitted" : "from the logs", start.robot.trunk_mass_scale,
               args.has("robot-mass") ? "from --robot-mass" : "the start world's");
  calibration::CalibrationResult result;
  const Status s = calibration::calibrate(log_ptrs, world, start, options, result);
  std::fprintf(stderr, "\n");
  std::signal(SIGINT, SIG_DFL);
  if (!s) {
    if (g_stop.load())
      return errors.failure("interrupted; the evaluations so far are in " +
                            options.progress_file.string() + " (--resume continues)");
    return errors.failure(s.message());
  }
  nlohmann::json logs_json = nlohmann::json::array();
  for (const std::string& path : args.positional()) logs_json.push_back(path);
  result.world.calibration["logs"] = logs_json;
  result.world.calibration["supply_voltage_from"] = fit_voltage ? "fit" : "logs";
  result.world.calibration["warnings"] = warnings;
  if (args.has("robot-mass"))
    result.world.calibration["robot_mass_kg"] = std::stod(args.get("robot-mass"));
  if (Status w = core::write_file_atomically(out, sim::to_json(result.world).dump(2) + "\n"); !w)
    return errors.failure(w.message());
  std::error_code error;
  std::filesystem::remove(options.progress_file, error);
  print_fit(result, out);
  if (!args.has("no-check"))
    if (Status c = print_prediction_check(args, log_ptrs, world, options.replay, result.world); !c)
      return errors.failure("prediction check: " + c.message());
  return 0;
}

STRIDE_COMMAND(calibrate, "fit the simulated robot to flight logs and write a world file",
               run_calibrate);
