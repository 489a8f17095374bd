// The simulator's world options by name: one table of names, units, defaults, ranges and help
// lines that the command-line flags (sim_cli.hpp: stride sim, stride-fw --hal sim, stride vbus
// --sim, stride identify/calibrate/replay), the task configs' world fields (`world` object or
// the old flat fields) and stride validate's step override all read, so that an option has one
// name, one range and one error message everywhere, and one place maps each name to a model.
//
// Names: the JSON key ("physics_step_us"); its flag is "--" with '-' for '_'
// ("--physics-step-us"). Errors read "<name as given>: <what is wrong>, got <value>", the name
// in the syntax it was given in.
//
// The physics step is checked against the firmware's real control period in one place,
// check_physics_step (SimWorld, the optimiser and stride validate call it with the period of
// the firmware they run).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::sim {

struct WorldOptionInfo {
  std::string_view key;           ///< JSON key
  std::string_view unit;          ///< "" for names
  std::string_view default_text;  ///< shown in help
  std::string_view help;
  std::vector<std::string_view> choices;  ///< the allowed names (empty: a number)
  double min = 0.0, max = 0.0;            ///< a number's range (integers for "us")
};

/// The named options of a world: base, engine, physics_step_us, servo_law, imu, contact.
const std::vector<WorldOptionInfo>& world_option_table();
/// The option of `key`, or null.
const WorldOptionInfo* find_world_option(std::string_view key);
/// "--physics-step-us" for "physics_step_us".
std::string world_option_flag(std::string_view key);
/// "base, engine, physics_step_us, ...": for an unknown-option error.
std::string world_option_keys();

/// Applies one option's value (as text: a name or a number) to `out`; `shown` is the name the
/// user gave (a key or a flag) for the error. base: "faithful" or "seed" (WorldOptions::apply;
/// a world file goes through world_file.hpp); the others set their part.
Status apply_world_option(const WorldOptionInfo& option, const std::string& value,
                          const std::string& shown, WorldOptions& out);

/// The physics step [ns] checked against its range (1..20000 us) and the control period [ns]
/// of the firmware that runs in the world: it must divide the period. `shown` names the option
/// as the user gave it; the message gives microseconds.
Status check_physics_step(std::int64_t step_ns, std::int64_t control_period_ns,
                          const std::string& shown = "physics_step_us");

/// Flag name of an option: world_option_flag, except base, which is --world (where it also
/// takes a world file).
std::string world_option_cli_flag(std::string_view key);

}  // namespace stride::sim
