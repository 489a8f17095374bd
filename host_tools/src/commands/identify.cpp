// `stride identify --out LOG`: plays the identification routine (firmware/scripts/
// IDENTIFICATION.md) in the simulator and records its flight log, as stride-fw --record does on
// the robot; the input of `stride replay` and `stride calibrate`. The run: identification_run.hpp.
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/cli_args.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/sim_hal/identification_run.hpp"
#include "stride/sim_hal/sim_cli.hpp"

namespace {

using stride::Status;
namespace sim = stride::sim;

const stride::tools::CommandErrors errors("identify");

/// The routine's parts and their lengths from the command line.
Status read_run(const stride::core::CliArgs& args, sim::IdentificationRun& run) {
  run.parts.clear();
  std::stringstream parts(args.get("parts"));
  for (std::string part; std::getline(parts, part, ',');) run.parts.push_back(part);
  if (run.parts.empty()) return Status::error("--parts: name at least one part");
  if (Status s = args.get_double("stand-s", run.stand_s); !s) return s;
  if (Status s = args.get_double("walk-s", run.walk_s); !s) return s;
  if (!(run.stand_s >= 0.0 && run.stand_s <= 600.0))
    return Status::error("--stand-s: must be in [0, 600], got " + args.get("stand-s"));
  if (!(run.walk_s >= 0.0 && run.walk_s <= 600.0))
    return Status::error("--walk-s: must be in [0, 600], got " + args.get("walk-s"));
  run.walk_in_place_s = run.walk_s;
  if (args.has("params")) run.firmware.params_file = args.get("params");
  return Status::ok();
}

/// What was recorded: the log's length and where each part starts (or one JSON object).
void print_summary(const sim::IdentificationSummary& summary, const std::filesystem::path& out,
                   const sim::WorldOptions& world, bool json) {
  if (json) {
    nlohmann::json parts_json = nlohmann::json::object();
    for (const auto& [name, start] : summary.part_start_s) parts_json[name] = start;
    const nlohmann::json j = {
        {"log", out.string()},
        {"ticks", summary.ticks},
        {"ticks_dropped", summary.ticks_dropped},
        {"fell", summary.fell},
        {"failure", summary.failure},
        {"part_start_s", parts_json},
        {"imu_bias",
         {{"accel_mps2",
           {summary.accel_bias_mps2.x(), summary.accel_bias_mps2.y(), summary.accel_bias_mps2.z()}},
          {"gyro_rad_s",
           {summary.gyro_bias_rad_s.x(), summary.gyro_bias_rad_s.y(),
            summary.gyro_bias_rad_s.z()}}}},
        {"world", sim::describe_world(world)}};
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("%s: %lld ticks (%.1f s) in %s\n", out.string().c_str(),
                static_cast<long long>(summary.ticks),
                static_cast<double>(summary.ticks) * summary.period_s,
                sim::describe_world(world).c_str());
    for (const auto& [name, start] : summary.part_start_s)
      std::printf("  %-15s from %6.2f s\n", name.c_str(), start);
  }
}

}  // namespace

int run_identify(int argc, char** argv) {
  stride::core::CliArgs args;
  args.option("help", "show this help", false);
  args.option("out", "the flight log to write (required)", true);
  args.option("parts", "comma-separated parts in order", true,
              "stand,identify_arms,identify_stand,identify_shift,identify_steps,walk");
  args.option("stand-s", "part stand: seconds standing still", true, "20");
  args.option("walk-s", "part walk: seconds walking in place, and forward", true, "10");
  args.option("params", "walk parameter file the firmware runs with (default: its defaults)", true);
  args.option("json", "print the summary as one JSON object", false);
  sim::declare_world_options(args);
  if (Status s = args.parse(argc, argv); !s) return errors.bad_input(s.message());
  if (args.has("help")) {
    std::printf(
        "usage: stride identify --out LOG [world options] [--parts LIST] [--params FILE]\n\n"
        "Plays the identification routine (firmware/scripts/IDENTIFICATION.md) in the simulated\n"
        "world and records its flight log, as `stride-fw --record` does on the robot: standing\n"
        "still, the scripts identify_arms, identify_stand, identify_shift and identify_steps,\n"
        "walking in place "
        "and a short walk. A world file (--world FILE.json) simulates a perturbed robot.\n\n%s",
        args.help().c_str());
    return 0;
  }
  if (!args.positional().empty())
    return errors.bad_input("unexpected argument '" + args.positional()[0] + "'");
  if (!args.has("out")) return errors.bad_input("--out: the flight log to write is required");
  const std::filesystem::path out = args.get("out");
  std::error_code error;
  if (out.has_parent_path() && !std::filesystem::is_directory(out.parent_path(), error))
    return errors.bad_input("--out: no such folder '" + out.parent_path().string() + "'");
  if (args.has("push"))
    return errors.bad_input("--push: not available in the identification routine");

  sim::IdentificationRun run;
  if (Status s = read_run(args, run); !s) return errors.bad_input(s.message());
  sim::WorldOptions world;
  if (Status s = sim::read_world_options(args, world); !s) return errors.bad_input(s.message());

  sim::IdentificationSummary summary;
  if (Status s = sim::record_identification(run, world, out, summary); !s)
    return errors.bad_input(s.message());
  print_summary(summary, out, world, args.has("json"));
  if (summary.fell || !summary.failure.empty()) {
    return errors.failure((summary.fell ? std::string("the robot fell") : summary.failure) +
                          " (the log up to there is kept)");
  }
  return 0;
}

STRIDE_COMMAND(identify, "play the identification routine in the simulator and record its log",
               run_identify);
