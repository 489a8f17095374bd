// Command-line options shared by `stride sim` and `stride-fw --hal sim`: they declare the
// same simulator options on a CliArgs and turn them into WorldOptions.
#pragma once

#include <string>
#include <vector>

#include "stride/core/cli_args.hpp"
#include "stride/sim_hal/sim_world.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::sim {

/// Declares every option of the world option table (world_spec.hpp) as a flag: --world,
/// --engine, --physics-step-us, ..., --push (repeatable).
void declare_world_options(core::CliArgs& args);
/// Reads the flags given into `out`; the error names the flag.
Status read_world_spec(const core::CliArgs& args, WorldSpec& out);
/// read_world_spec, then the world it describes (whose control period the caller sets).
Status read_world_options(const core::CliArgs& args, WorldOptions& out);

/// Every value of the repeatable option `name` as engines, each value one engine or a
/// comma-separated list ("simbody,mujoco"), in order, each engine once; the error names
/// --name.
Status read_engine_list(const core::CliArgs& args, const std::string& name,
                        std::vector<EngineKind>& out);

/// One line naming the world's engine, servo law, IMU, contact and physics step, e.g.
/// "simbody, identified servo law, cm730 IMU, turf, step 2000 us".
std::string describe_world(const WorldOptions& options);

}  // namespace stride::sim
