// A simulated world as its options name it (WorldSpec), and the one table of those options:
// names, units, defaults, ranges and help lines. The command-line flags (sim_cli.hpp: stride
// sim, stride-fw --hal sim, stride vbus --sim, stride identify/calibrate/replay), a task
// config's `world` object (and its old flat fields), run.json and stride validate's overrides
// all read an option through this table, so that it has one name, one range and one error
// message everywhere. WorldSpec::to_options is the one place that maps the names to the models
// (WorldOptions: servo laws, IMU chains, contact parameters).
//
// Names: the JSON key ("physics_step_us"); its flag is "--" with '-' for '_'
// ("--physics-step-us"), except base, whose flag is --world. Errors read
// "<name as given>: <what is wrong>, got <value>", the name in the syntax it was given in.
//
// Units: the user's units are the table's (the step in microseconds, impulses in N s, times in
// s); WorldOptions holds the step in nanoseconds, the control loop's time unit.
//
// The physics step is checked against the firmware's real control period in one place,
// check_physics_step (SimWorld, the optimiser and stride validate call it with the period of
// the firmware they run).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/sim_hal/world_file.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::sim {

/// What an option's value is.
enum class WorldValue : std::uint8_t {
  kName,     ///< one of `choices`
  kInteger,  ///< an integer in [min, max]
  kNumber,   ///< a real number in [min, max]
  kPath,     ///< a file
  kPushes,   ///< repeatable "T,DIR,IMPULSE" (parse_push)
};

struct WorldOptionInfo {
  std::string_view key;           ///< JSON key
  std::string_view unit;          ///< "" for names and plain numbers
  std::string_view default_text;  ///< shown in help ("" for none)
  std::string_view help;
  WorldValue value = WorldValue::kName;
  std::vector<std::string_view> choices;  ///< kName: the allowed names
  double min = 0.0, max = 0.0;            ///< kInteger, kNumber: the range (inclusive)
};

/// Every option of a world, in the order the help lists them: base, engine, physics_step_us,
/// servo_law, imu, mag_disturbance, contact, friction, urdf, noise, seed, friction_range,
/// mass_range, strength_range, latency_probability, contact_range, com_range, latency_ticks,
/// push.
const std::vector<WorldOptionInfo>& world_option_table();
/// The option of `key`, or null.
const WorldOptionInfo* find_world_option(std::string_view key);
/// "--physics-step-us" for "physics_step_us".
std::string world_option_flag(std::string_view key);
/// Flag name of an option: world_option_flag, except base, which is --world (where it also
/// takes a world file).
std::string world_option_cli_flag(std::string_view key);
/// "base, engine, physics_step_us, ...": for an unknown-option error.
std::string world_option_keys();
/// "faithful or seed": a named option's choices.
std::string world_option_choices(const WorldOptionInfo& option);

/// A world by its options, each unset part taken from the base world. Plain values in the
/// table's units, independent of the order they were given in.
struct WorldSpec {
  WorldPreset base = WorldPreset::kFaithful;
  std::optional<WorldFile> file;    ///< a world file as the base (its base world and calibration)
  std::filesystem::path file_path;  ///< where `file` came from ("" for an inline object)
  EngineKind engine = EngineKind::kSimbody;
  std::int64_t physics_step_us = 2000;
  std::optional<ServoLaw> servo_law;        ///< unset: the base world's
  std::optional<ImuKind> imu;               ///< unset: the base world's
  std::optional<double> mag_disturbance;    ///< [gauss]; unset: MagnetometerSpec's
  std::optional<std::string> contact;       ///< "turf", "seed", "soft", "hard"; unset: the base's
  std::optional<double> friction;           ///< Coulomb coefficient; unset: the contact's
  std::filesystem::path urdf;               ///< empty: the igus model
  std::shared_ptr<const RobotModel> model;  ///< `urdf` parsed when it was set
  bool noise = true;                        ///< sensor noise and per-reset IMU bias
  std::uint64_t seed = 1;
  /// Per-reset randomisation: friction, mass and strength ranges, latency probability, ground.
  Randomisation randomise;
  std::optional<int> latency_ticks;  ///< unset: the world file's (nominal 0)
  std::vector<TorsoPush> pushes;

  /// Sets one option from its text (a name, a number, a path, a world file for base, one push
  /// for push, which adds it); `shown` is the name the user gave (a key or a flag) for the
  /// error. Nothing changes on an error.
  Status set(const WorldOptionInfo& option, const std::string& value, const std::string& shown);
  /// set() by key; an unknown key is an error naming it and the known keys.
  Status set(std::string_view key, const std::string& value, const std::string& shown);
  /// True if `key` was given a value other than its default.
  bool is_set(std::string_view key) const;

  /// The world these options describe (the one mapping from names to models). The control
  /// period is WorldOptions' default; the caller sets the firmware's.
  WorldOptions to_options() const;
};

/// Reads a `world` object of table keys into `out` (onto what it holds): values are strings,
/// numbers or booleans, `push` a list of "T,DIR,IMPULSE", `base` a name, a world file's path
/// or its object. An unknown key is an error naming `prefix` + key and the known keys.
Status read_world_spec(const nlohmann::json& object, const std::string& prefix, WorldSpec& out);
/// The options that differ from their defaults as such an object (base and physics_step_us
/// always; a world file by value, a URDF by its absolute path).
nlohmann::json to_json(const WorldSpec& spec);

/// Largest impulse a push takes [N s] (about 3 m/s of the igus robot's 6.5 kg).
inline constexpr double kMaxPushImpulse = 20.0;
/// Reads one push "T,DIR,IMPULSE": T [s] in [0, duration_s), DIR forward, backward, left,
/// right or an angle in degrees in [-360, 360] (anticlockwise from the robot's heading),
/// IMPULSE [N s] in (0, kMaxPushImpulse]. The error names `shown` and what is wrong.
Status parse_push(const std::string& text, double duration_s, TorsoPush& out,
                  const std::string& shown = "--push");
/// The push as parse_push reads it back ("5.2,90,1.5": the direction in degrees).
std::string push_text(const TorsoPush& push);

/// The physics step [ns] checked against its range (1..20000 us) and the control period [ns]
/// of the firmware that runs in the world: it must divide the period. `shown` names the option
/// as the user gave it; the message gives microseconds.
Status check_physics_step(std::int64_t step_ns, std::int64_t control_period_ns,
                          const std::string& shown = "physics_step_us");

}  // namespace stride::sim
