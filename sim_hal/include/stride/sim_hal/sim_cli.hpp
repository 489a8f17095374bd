// Command-line options shared by `stride sim` and `stride-fw --hal sim`: they declare the
// same simulator options on a CliArgs and turn them into WorldOptions.
#pragma once

#include <string>
#include <vector>

#include "stride/core/cli_args.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {

/// Declares --seed, --noise on|off, --physics-step-us, --urdf, --world faithful|seed, --imu,
/// --servo-law, --engine, --contact, --push.
void declare_world_options(core::CliArgs& args);
/// Reads them into `out` (whose control period the caller sets). The error names the option.
Status read_world_options(const core::CliArgs& args, WorldOptions& out);

/// One line naming the world's engine, servo law, IMU, contact and physics step, e.g.
/// "simbody, identified servo law, cm730 IMU, turf, step 2000 us".
std::string describe_world(const WorldOptions& options);

/// Largest impulse `--push` accepts [N s] (about 3 m/s of the igus robot's 6.5 kg).
inline constexpr double kMaxPushImpulse = 20.0;
/// Reads one `--push T,DIR,IMPULSE`: T [s] in [0, duration_s), DIR forward, backward, left,
/// right or an angle in degrees in [-360, 360] (anticlockwise from the robot's heading),
/// IMPULSE [N s] in (0, kMaxPushImpulse]. The error names --push and what is wrong.
Status parse_push(const std::string& text, double duration_s, TorsoPush& out);

}  // namespace stride::sim
