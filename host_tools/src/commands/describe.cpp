// `stride describe`: writes the firmware's robot description (masses, centres of mass and joint
// frames; fw::RobotDescription) from a URDF, so the firmware gets its rigid-body model without a
// URDF parser. The shipped firmware/config/robot_description.json is its output for the shipped
// URDF; run it again for a robot whose URDF changed.
#include <cstdio>
#include <string>

#include "stride/core/atomic_file.hpp"
#include "stride/core/cli_args.hpp"
#include "stride/firmware/robot_description.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/sim_hal/robot_description_writer.hpp"
#include "stride/sim_hal/robot_model.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace {

const stride::tools::CommandErrors errors("describe");

}  // namespace

int run_describe(int argc, char** argv) {
  stride::core::CliArgs args;
  args.option("urdf", "robot model to describe", true,
              stride::sim::RobotModel::igus_path().string())
      .option("servo-table", "servo table the description must match", true,
              stride::fw::ServoTable::default_path().string())
      .option("out", "file to write (atomically); default: standard output", true, "")
      .option("help", "show this help", false);
  if (auto st = args.parse(argc, argv); !st) return errors.bad_input(st.message());
  if (args.has("help")) {
    std::printf(
        "usage: stride describe [--urdf FILE] [--servo-table FILE] [--out FILE]\n\n"
        "Writes the firmware's robot description (firmware/config/robot_description.json):\n"
        "per servo joint its parent, origin, axis, and its child link's mass and centre of\n"
        "mass, read from the URDF. stride-fw loads it at start-up for the walk's compliance\n"
        "compensation.\n\n%s",
        args.help().c_str());
    return 0;
  }
  if (!args.positional().empty())
    return errors.bad_input("unexpected argument '" + args.positional()[0] + "'");
  stride::fw::ServoTable servos;
  if (auto st = stride::fw::ServoTable::load(args.get("servo-table"), servos); !st)
    return errors.bad_input("--servo-table: " + st.message());
  stride::sim::RobotModel model;
  const std::filesystem::path urdf = args.get("urdf");
  if (auto st = stride::sim::RobotModel::load_file(urdf, model); !st)
    return errors.bad_input("--urdf: " + st.message());
  std::string text;
  if (auto st = stride::sim::write_robot_description(model, stride::sim::igus_servo_joints(),
                                                     servos, urdf.filename().string(), text);
      !st)
    return errors.bad_input("--urdf: " + st.message());
  // What is written must load back: the firmware refuses to start on anything else.
  stride::fw::RobotDescription check;
  if (auto st = stride::fw::RobotDescription::parse(text, "description", servos, check); !st)
    return errors.bad_input(st.message());
  const std::string out = args.get("out");
  if (out.empty()) {
    std::fputs(text.c_str(), stdout);
    return 0;
  }
  if (auto st = stride::core::write_file_atomically(out, text); !st)
    return errors.bad_input("--out: " + st.message());
  std::fprintf(stderr, "stride describe: %s: %zu joints, %.4f kg\n", out.c_str(),
               check.joints().size(), check.total_mass());
  return 0;
}

STRIDE_COMMAND(describe, "write the firmware's robot description from a URDF", run_describe);
