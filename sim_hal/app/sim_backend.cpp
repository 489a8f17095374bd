// The `sim` HAL backend of stride-fw: the firmware runs against the Simbody world in lockstep
// (as fast as it computes), or paced by the real clock with --realtime (RealtimeRobot).
#include <nlohmann/json.hpp>

#include "stride/firmware/firmware.hpp"
#include "stride/firmware/hal_registry.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_cli.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace {

void declare(stride::core::CliArgs& args) {
  stride::sim::declare_world_options(args);
  args.option("realtime", "sim: pace the simulation at real time", false);
}

/// The world options as the user gave them, and the step against the firmware's period.
stride::Status read_options(const stride::core::CliArgs& args, std::int64_t period_ns,
                            stride::sim::WorldOptions& options) {
  if (stride::Status s = stride::sim::read_world_options(args, options); !s) return s;
  options.control_period_ns = period_ns;
  return stride::sim::check_physics_step(options.physics_step_ns, period_ns, "--physics-step-us");
}

stride::Status check(const stride::core::CliArgs& args, std::int64_t period_ns) {
  stride::sim::WorldOptions options;
  return read_options(args, period_ns, options);
}

stride::Status make(const stride::core::CliArgs& args, std::int64_t period_ns,
                    stride::fw::HalInstance& out) {
  stride::sim::WorldOptions options;
  if (stride::Status s = read_options(args, period_ns, options); !s) return s;
  std::unique_ptr<stride::sim::SimWorld> world;
  if (stride::Status s = stride::sim::SimWorld::create(options, world); !s) return s;
  auto robot = std::make_unique<stride::sim::SimRobot>(std::move(world));
  stride::sim::SimRobot* sim = robot.get();
  out.robot = std::move(robot);
  out.paced_by_clock = args.has("realtime");
  out.report = [sim](nlohmann::json& report) {
    const stride::sim::SimWorld& w = sim->world();
    const stride::sim::GroundTruth g = w.ground_truth();
    report["sim"] = {{"sim_time_s", w.time_s()},
                     {"status", stride::sim::to_string(w.status())},
                     {"failure_reason", w.failure_reason()},
                     {"torso_height_m", g.torso.translation().z()},
                     {"upright", g.torso.linear()(2, 2)},
                     {"state_hash", stride::sim::hash_hex(w.state_hash())}};
  };
  return {};
}

/// --world seed is the thesis's world and its walk, as for `stride sim`: the walk defaults of
/// then (config/seed-walk.json) unless --params names a file.
std::string default_params(const stride::core::CliArgs& args) {
  stride::sim::WorldSpec spec;
  if (!stride::sim::read_world_spec(args, spec)) return "";  // check() reports the error
  if (spec.base != stride::sim::WorldPreset::kSeed || spec.file) return "";
  return (stride::fw::data_dir() / "config" / "seed-walk.json").string();
}

}  // namespace

STRIDE_HAL_BACKEND_WITH_PARAMS(sim,
                               "Simbody simulation in lockstep (--realtime: paced by the clock)",
                               declare, check, make, default_params);
