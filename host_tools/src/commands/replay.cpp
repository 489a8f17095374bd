// `stride replay LOG`: replays a flight log (stride-fw --record) against the simulated robot,
// window by window, and reports how far the simulation is from what the robot sensed (table,
// --json summary, --html page with the traces overlaid). The replay itself: log_replay.hpp;
// its report: stride/calibration/replay_report.hpp.
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "stride/calibration/replay_report.hpp"
#include "stride/core/atomic_file.hpp"
#include "stride/core/cli_args.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/sim_hal/log_replay.hpp"
#include "stride/sim_hal/sim_cli.hpp"

namespace {

using stride::Status;
namespace sim = stride::sim;
namespace calibration = stride::calibration;
namespace fw = stride::fw;
namespace core = stride::core;

const stride::tools::CommandErrors errors("replay");

/// An output path whose folder does not exist is bad input, found before the replay runs.
Status check_output_path(const std::string& option, const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (path.empty() || std::filesystem::is_directory(path, error))
    return Status::error("--" + option + ": not a file name: '" + path + "'");
  if (!parent.empty() && !std::filesystem::is_directory(parent, error))
    return Status::error("--" + option + ": no such folder '" + parent.string() + "'");
  return Status::ok();
}

void declare_options(core::CliArgs& args) {
  args.option("help", "show this help", false);
  args.option("window", "window length [s]: the robot is placed in the logged state at each start",
              true, "2");
  args.option("html", "write a page with the logged and simulated traces overlaid", true);
  args.option("json", "print the summary as one JSON object", false);
  args.option("servo-table", "the firmware's servo table (must be the log's)", true,
              fw::ServoTable::default_path().string());
  args.option("robot-description", "the firmware's rigid-body model (must be the log's)", true,
              fw::RobotDescription::default_path().string());
  args.option("allow-truncated", "replay a cut or damaged log up to its last whole block", false);
  args.option("logged-speeds", "start each window with the logged joint speeds (default: at rest)",
              false);
  args.option("no-sink",
              "place the lowest point on the grass top (default: sunk to carry the "
              "robot's weight)",
              false);
  sim::declare_world_options(args);
}

void print_help(const core::CliArgs& args) {
  std::printf(
      "usage: stride replay LOG [world options] [--window S] [--html FILE] [--json]\n\n"
      "Replays a flight log (stride-fw --record) against the simulated robot: for each window\n"
      "of S seconds the robot is placed in the logged state (joint angles, trunk attitude from\n"
      "the IMU, feet on the ground) and fed the logged commands; prints the RMS errors of the\n"
      "simulated sensors against the logged ones (firmware/src/recorder/FLIGHT_LOG.md).\n\n%s",
      args.help().c_str());
}

}  // namespace

int run_replay(int argc, char** argv) {
  core::CliArgs args;
  declare_options(args);
  if (Status s = args.parse(argc, argv); !s) return errors.bad_input(s.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  if (args.positional().size() != 1)
    return errors.bad_input("expected one flight log (stride replay LOG)");
  const std::string log_path = args.positional()[0];
  double window_s = 0.0;
  if (Status s = args.get_double("window", window_s); !s) return errors.bad_input(s.message());
  if (!(window_s > 0.0) || window_s > 1e6)
    return errors.bad_input("--window: must be a positive number of seconds, got " +
                            args.get("window"));
  if (args.has("push"))
    return errors.bad_input("--push: not available in replay (the logged commands are replayed)");
  sim::WorldOptions world;
  if (Status s = sim::read_world_options(args, world); !s) return errors.bad_input(s.message());
  if (args.has("html"))
    if (Status s = check_output_path("html", args.get("html")); !s)
      return errors.bad_input(s.message());

  // The firmware files the log must have been recorded with.
  fw::ServoTable servos;
  if (Status s = fw::ServoTable::load(args.get("servo-table"), servos); !s)
    return errors.bad_input("--servo-table: " + s.message());
  fw::RobotDescription robot;
  if (Status s = fw::RobotDescription::load(args.get("robot-description"), servos, robot); !s)
    return errors.bad_input("--robot-description: " + s.message());

  fw::FlightLog log;
  if (Status s = fw::read_flight_log(log_path, log); !s) return errors.bad_input(s.message());
  if (Status s = sim::check_replayable(log, servos, robot, args.has("allow-truncated")); !s)
    return errors.bad_input(log_path + ": " + s.message());
  if (Status s = sim::check_window(log, window_s); !s) return errors.bad_input(s.message());

  sim::ReplayOptions options;
  options.window_s = window_s;
  options.keep_traces = args.has("html");
  options.start_with_logged_speeds = args.has("logged-speeds");
  options.sink_into_grass = !args.has("no-sink");
  sim::ReplayResult result;
  if (Status s = sim::replay_flight_log(log, world, options, result); !s)
    return errors.failure(s.message());

  nlohmann::json firmware = log.header.value("firmware", nlohmann::json::object());
  if (!firmware.is_object()) firmware = nlohmann::json::object();
  const std::vector<std::pair<std::string, std::string>> facts = {
      {"log", log_path},
      {"log_hal", log.header.value("hal", "")},
      {"firmware", firmware.value("version", "") + " " + firmware.value("git", "")},
      {"world", sim::describe_world(world) + ", seed " + args.get("seed") + ", noise " +
                    args.get("noise") + (args.has("urdf") ? ", urdf " + args.get("urdf") : "")},
      {"start", args.has("logged-speeds") ? "logged joint angles and speeds"
                                          : "logged joint angles, at rest"}};
  if (args.has("html")) {
    const std::string page = calibration::replay_html(result, "Stride replay: " + log_path, facts);
    if (Status s = core::write_file_atomically(args.get("html"), page); !s)
      return errors.failure(s.message());
  }
  if (args.has("json")) {
    std::printf("%s\n", calibration::replay_summary_json(result, facts).dump().c_str());
  } else {
    std::printf("%s: %zu windows of %.2f s in %s\n", log_path.c_str(), result.windows.size(),
                static_cast<double>(result.window_ticks) * result.period_s,
                facts[3].second.c_str());
    std::printf("%s", calibration::replay_table(result).c_str());
    if (result.ticks_not_replayed > 0)
      std::printf("%zu of %zu logged ticks not replayed (the tail shorter than a window, gaps)\n",
                  result.ticks_not_replayed, result.ticks_in_log);
  }
  return 0;
}

STRIDE_COMMAND(replay, "replay a flight log against the simulated robot: RMS errors, traces",
               run_replay);
