// Command-line options shared by `stride sim` and `stride-fw --hal sim`: they declare the
// same simulator options on a CliArgs and turn them into WorldOptions.
#pragma once

#include "stride/firmware/cli_args.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {

/// Declares --seed, --noise on|off, --physics-step-us, --urdf, --imu, --servo-law, --engine.
void declare_world_options(fw::CliArgs& args);
/// Reads them into `out` (whose control period the caller sets). The error names the option.
Status read_world_options(const fw::CliArgs& args, WorldOptions& out);

}  // namespace stride::sim
