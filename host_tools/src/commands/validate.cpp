// `stride validate RUN`: re-scores Ind_O and the picks of a robot run on worlds the run never
// saw (the other engine, fresh noisy seeds, wider randomisation, half the physics step, the soft
// and the hard ground) and
// writes RUN/validation.json (optimiser/run/validation.hpp); a table on stdout, or --json.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/cli_args.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/optimiser/run/validation.hpp"
#include "stride/sim_hal/sim_cli.hpp"

namespace {

namespace opt = stride::opt;
using stride::Status;

const stride::tools::CommandErrors errors("validate");

void declare_options(stride::core::CliArgs& args) {
  args.option("engine",
              "engine of the other-engine worlds, repeatable: simbody|mujoco "
              "(default: every engine the run did not use)")
      .option("member",
              "also validate this front member (pareto.csv row, front/NNN.json), repeatable")
      .option("seeds", "fresh seeds per world (default: the config's validate.seeds, 10)")
      .option("physics-step-us", "physics step of the step world [us] (default: half the run's)")
      .option("jobs", "episodes in parallel (default: all cores)")
      .option("json", "print the result as one JSON object", false)
      .option("help", "show this help", false);
}

void print_help(const stride::core::CliArgs& args) {
  std::printf(
      "usage: stride validate RUN [--member ROW]... [--engine E]... [--seeds N]\n"
      "       [--physics-step-us US] [--jobs N] [--json]\n"
      "Re-scores Ind_O and the picks of the robot run in RUN (fastest, most stable, knee;\n"
      "kick: least sway, longest kick; --member: any other front member) on worlds the run never "
      "saw, each with N fresh seeds\n"
      "and IMU noise on: the other engine(s), fresh seeds, wider randomisation (1.5x the\n"
      "run's friction, mass and strength ranges, at least 0.3 / 0.075 / 0.15, one tick of\n"
      "latency in half of the worlds), half the physics step, and the soft and the hard\n"
      "ground (deep turf, studs sinking 4 mm; carpet, 0.4 mm). Per individual and world:\n"
      "reached fraction, falls, median objectives, the gate (>= 80 %% of the seeds reached\n"
      "without a fall, median within 25 %% of its own value in the run) and the gain kept\n"
      "against Ind_O; then the same in words: where each holds (passes the gate), why it\n"
      "fails elsewhere, the pick that holds in most worlds. Writes RUN/validation.json;\n"
      "`stride report RUN` shows it.\n\n%s",
      args.help().c_str());
}

}  // namespace

int run_validate(int argc, char** argv) {
  stride::core::CliArgs args;
  declare_options(args);
  if (auto st = args.parse(argc, argv); !st) return errors.bad_input(st.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  if (args.positional().size() != 1) return errors.bad_input("expected one run directory");
  const std::filesystem::path dir = args.positional()[0];
  std::vector<std::size_t> members;
  for (const std::string& text : args.get_all("member")) {
    char* end = nullptr;
    const long long row = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || row < 0 || row > 100000)
      return errors.bad_input("--member: expected a pareto.csv row (0, 1, ...), got '" + text +
                              "'");
    members.push_back(static_cast<std::size_t>(row));
  }
  opt::ValidationSubject subject;
  if (auto st = opt::load_validation_subject(dir, subject, members); !st)
    return errors.bad_input(st.message());
  opt::ValidationOptions options;
  if (auto st = stride::sim::read_engine_list(args, "engine", options.engines); !st)
    return errors.bad_input(st.message());
  options.seeds = subject.config.validate_seeds;
  std::int64_t v = 0;
  if (args.has("seeds")) {
    if (auto st = args.get_int("seeds", v); !st) return errors.bad_input(st.message());
    if (v < 1 || v > 1000)
      return errors.bad_input("--seeds: " + std::to_string(v) + " is outside [1, 1000]");
    options.seeds = static_cast<int>(v);
  }
  if (args.has("physics-step-us")) {
    // Its range here (the world option table), the firmware's period in validation_worlds
    // below (check_physics_step).
    stride::sim::WorldSpec world;
    if (auto st = world.set("physics_step_us", args.get("physics-step-us"), "--physics-step-us");
        !st)
      return errors.bad_input(st.message());
    options.physics_step_ns = world.physics_step_us * 1000;
  }
  options.jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (args.has("jobs")) {
    if (auto st = args.get_int("jobs", v); !st) return errors.bad_input(st.message());
    if (v < 1 || v > 1024)
      return errors.bad_input("--jobs: " + std::to_string(v) + " is outside [1, 1024]");
    options.jobs = static_cast<int>(v);
  }
  {
    // Option errors (a step that does not divide the period) are bad input, before any work.
    std::vector<opt::ValidationWorld> worlds;
    if (auto st = opt::validation_worlds(opt::RobotTask(subject.config), options, worlds); !st)
      return errors.bad_input(st.message());
  }
  options.progress = opt::validation_progress_printer(isatty(STDERR_FILENO) != 0);
  nlohmann::json result;
  if (auto st = opt::run_validation(subject, options, result); !st) {
    return errors.failure(st.message());
  }
  if (auto st = opt::write_validation_file(dir, result); !st) {
    return errors.failure(st.message());
  }
  if (args.has("json")) {
    std::printf("%s\n", result.dump().c_str());
    return 0;
  }
  std::printf("%s", opt::validation_text(result).c_str());
  std::printf("written: %s\n", (dir / "validation.json").c_str());
  return 0;
}

STRIDE_COMMAND(validate, "re-score a run's picks on worlds it never saw (validation.json)",
               run_validate);
