// A simulated world as its options name it (WorldSpec), and the one table of those options:
// names, units, ranges and help lines, each row bound to its WorldSpec field (whose member
// initialiser is the option's default, the one place a default is written). The command-line
// flags (sim_cli.hpp: stride sim, stride-fw --hal sim, stride vbus --sim, stride
// identify/calibrate/replay), a task config's `world` object (and its old flat fields and its
// trials' randomisation), run.json and stride validate's overrides all read an option through
// this table, so that it has one name, one range and one error message everywhere.
// WorldSpec::to_options is the one place that maps the names to the models (WorldOptions: servo
// laws, IMU chains, contact parameters).
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

struct WorldSpec;

/// What an option's value is.
enum class WorldValue : std::uint8_t {
  kWorld,    ///< a named world (one of `choices`) or a world file (a path or, in JSON, an object)
  kName,     ///< one of `choices`
  kInteger,  ///< an integer in [min, max]
  kNumber,   ///< a real number in [min, max]
  kPath,     ///< a file
  kPushes,   ///< repeatable "T,DIR,IMPULSE" (parse_push)
};

/// One option: its name, help and range, and its binding to its WorldSpec field. Everything
/// that handles options (WorldSpec::set and is_set, to_json, read_world_spec, the flags and
/// their help) loops over the table and reaches the field through `set` and `get` only, so that
/// adding an option is one row (and its field).
struct WorldOptionInfo {
  std::string_view key;   ///< JSON key
  std::string_view unit;  ///< "" for names and plain numbers
  /// Shown in help ("" for none). Left empty in the table's rows for an option with a value by
  /// default: the table fills it in from `get` of a default WorldSpec, so that the help shows
  /// the value the code uses. An option unset by default says what it then is.
  std::string default_text;
  std::string_view help;
  WorldValue value = WorldValue::kName;
  std::vector<std::string_view> choices;  ///< kWorld, kName: the allowed names
  double min = 0.0, max = 0.0;            ///< kInteger, kNumber: the range (inclusive)
  /// to_json writes the option even at its default (base and physics_step_us).
  bool always_written = false;
  /// A per-reset randomisation range (a field of Randomisation): a task config's trial
  /// randomisation reads and writes it too (optimiser/src/tasks/task_config.cpp).
  bool randomisation = false;
  /// Stores a checked value in the field: `text` as given (a name in `choices`, a number, a
  /// path, one push) and, for kInteger and kNumber, `number` its value in [min, max]. A value
  /// whose check needs its meaning (a world file, a URDF, a push) is checked here; the error
  /// names `shown`. Nothing changes on an error.
  Status (*set)(WorldSpec& spec, const std::string& text, double number,
                const std::string& shown) = nullptr;
  /// The field as a `world` object holds it; null when unset (an optional field without a
  /// value, no URDF, no pushes). An option is set when this differs from a default WorldSpec's.
  nlohmann::json (*get)(const WorldSpec& spec) = nullptr;
  /// kPushes: empties the list (a `world` object's list replaces what it held).
  void (*clear)(WorldSpec& spec) = nullptr;
};

/// Every option of a world, in the order the help lists them: base, engine, physics_step_us,
/// servo_law, imu, mag_disturbance, contact, friction, urdf, noise, seed, friction_range,
/// mass_range, strength_range, latency_probability, contact_range, com_range, servo_friction_min,
/// servo_friction_max, servo_torque_min, servo_torque_max, supply_min, supply_max, latency_ticks,
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
/// table's units, independent of the order they were given in. Its member initialisers are
/// the world's defaults, the one place they are written: the command line's default world is
/// WorldSpec{}.to_options() (the faithful world, noise on), and the help's defaults are read
/// from a default WorldSpec.
struct WorldSpec {
  WorldPreset base = WorldPreset::kFaithful;
  std::optional<WorldFile> file;    ///< a world file as the base (its base world and calibration)
  std::filesystem::path file_path;  ///< where `file` came from ("" for an inline object)
  EngineKind engine = EngineKind::kSimbody;
  std::int64_t physics_step_us = kDefaultPhysicsStepUs;
  std::optional<ServoLaw> servo_law;        ///< unset: the base world's
  std::optional<ImuKind> imu;               ///< unset: the base world's
  std::optional<double> mag_disturbance;    ///< [gauss]; unset: MagnetometerSpec's
  std::optional<std::string> contact;       ///< "turf", "seed", "soft", "hard"; unset: the base's
  std::optional<double> friction;           ///< Coulomb coefficient; unset: the contact's
  std::filesystem::path urdf;               ///< empty: the igus model
  std::shared_ptr<const RobotModel> model;  ///< `urdf` parsed when it was set
  bool noise = true;                        ///< sensor noise and per-reset IMU bias
  std::uint64_t seed = kDefaultWorldSeed;
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
  /// A world file as the base (`path` where it came from, "" for a `world` object's).
  void use_world_file(WorldFile world, std::filesystem::path path = {});

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
