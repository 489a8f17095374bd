// Validation of a robot run (`stride validate`, issue 21): Ind_O and the picks re-scored on
// worlds the run never saw, and how much of each pick's gain over Ind_O survives there.
//
// Individuals: Ind_O (run.json's start genome) and the picks of `stride report` (best Obj1,
// best Obj2, knee: report::run_picks; a member picked twice appears once).
// Worlds (each run with N fresh seeds, trial_seed + 1000 + i, i < N, never a seed of the run's
// trials; IMU noise on in all of them):
//   engine E            every engine the run was not scored on (or the --engine list), with the
//                       run's randomisation
//   fresh seeds         the run's (first) engine and randomisation
//   wider randomisation friction, masses and servo strength at 1.5x the run's ranges, at least
//                       1.5x the robust defaults (0.3, 0.075, 0.15), at most 0.9; one control
//                       tick of command latency in half of the worlds (latency probability 0.5);
//                       the ground range at 1.5x the run's (none if the run had none).
//                       sim_hal has no centre-of-mass randomisation: the mass scale per link
//                       moves the whole robot's centre of mass only through the link masses.
//   servos off the model every servo's friction x0.8-1.6 and motor torque x0.8-1.05, the supply
//                       12.0-16.8 V, each drawn per seed (kOffModelServos, issue 54), one tick of
//                       latency in half of the worlds, beside the run's randomisation; not
//                       for a run whose trials draw the servos already (its fresh seeds are it)
//   half step           the physics step halved (or --physics-step-us), the run's randomisation
//   ground soft         the soft ground (deep turf, studs sink 4 mm; sim::ContactOptions::soft),
//   ground hard         the hard one (carpet, 0.4 mm): the run's engine, friction and
//                       randomisation, no ground range
// A world that fails mid-episode (NaN, explosion) is a fall with its reason; a world that cannot
// be built (an engine not in this build) is reported as unavailable with the reason.
//
// Per individual and world: reached (walk: the goal without a fall; walk-omni: every segment
// without a fall; kick: no fall and the ball at least 0.5 m), falls, the median of each
// objective over the seeds. Gate: at least 80 % of the seeds reached (8 of 10) and the median
// of the task's measure (walk: time to the goal, Obj1; walk-omni: the speed score, Obj1; kick:
// 1 / ball distance, Obj2) no worse than the individual's own value in the run's world (its
// logged objective) by more than 25 % of that value. Gain kept per objective (picks only, and
// only where Ind_O passes the gate in that world):
//   (Ind_O's median - the pick's median) in the world / (Ind_O's - the pick's) in the run.
// The result is deterministic: jobs are indexed, seeds fixed, no wall times recorded.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/optimiser/nsga2/genome.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"

namespace stride::opt {

inline constexpr double kGateMinReachedFraction = 0.8;
inline constexpr double kGateMaxWorseFraction = 0.25;
/// First of the validation seeds, above trial_seed (the run's trials use trial_seed + k, k <
/// trials <= 1000).
inline constexpr std::uint64_t kValidationSeedOffset = 1000;

/// The "servos off the model" world's draws (issue 54 point 2): worn gears to a smooth new
/// servo, a weaker batch to the datasheet, a battery late in a half to a full 4S LiPo.
inline constexpr struct {
  double servo_friction_min = 0.8, servo_friction_max = 1.6;
  double servo_torque_min = 0.8, servo_torque_max = 1.05;
  double supply_min_v = 12.0, supply_max_v = 16.8;
} kOffModelServos{};

struct ValidationOptions {
  /// The engines of the "engine E" worlds; empty: every engine the run did not use.
  std::vector<sim::EngineKind> engines;
  int seeds = 10;
  /// Physics step of the "half step" world [ns]; 0: half the run's.
  std::int64_t physics_step_ns = 0;
  int jobs = 1;  ///< evaluation threads
  /// Called on the calling thread after each episode (done, total).
  std::function<void(std::size_t, std::size_t)> progress;
};

/// An individual to validate.
struct ValidationIndividual {
  std::string name;  ///< "Ind_O", "fastest, knee", ...
  std::string file;  ///< front file, empty for Ind_O
  Genome genome;
  std::vector<double> run_objectives;  ///< its score in the run's own world (logged)
};

/// What a run directory offers for validation: its task, Ind_O and the picks.
struct ValidationSubject {
  std::filesystem::path dir;
  TaskConfig config;
  std::vector<ValidationIndividual> individuals;  ///< Ind_O first
};

/// Reads a run directory: Ind_O, the picks and, after them, the front members of the pareto.csv
/// rows `members` that are not picks (named "front/NNN.json"). Every error is bad input (one
/// line naming what is wrong): not a robot run, no run.json, a damaged task config, no picks
/// (no front members), a member row that the front does not have.
Status load_validation_subject(const std::filesystem::path& dir, ValidationSubject& out,
                               const std::vector<std::size_t>& members = {});

/// One validation world: its name, its options by name (the run's world, RobotTask::world_spec,
/// with the validation's changes; the seed is set per episode) and the seeds.
struct ValidationWorld {
  std::string name;
  sim::WorldSpec world;
  std::vector<std::uint64_t> seeds;
};
/// The worlds for a task, each the run's first trial world (its WorldSpec) with IMU noise on
/// and the world's changes set as options; bad options (an engine list, a step that does not
/// divide the control period or whose half is not a whole microsecond) are an error naming the
/// option.
Status validation_worlds(const RobotTask& task, const ValidationOptions& options,
                         std::vector<ValidationWorld>& out);
/// The options episode `seed` (index into world.seeds) of `world` runs in: the world's spec with
/// that seed, through RobotTask::world_options (WorldSpec::to_options and the task's additions).
sim::WorldOptions validation_episode_world(const RobotTask& task, const ValidationWorld& world,
                                           std::size_t seed);

/// The format validation.json is written in: each world's options are a `world` object of the
/// world option table's keys (sim::to_json(WorldSpec)). "stride-validation-1" files had the
/// figures in the world entry itself (imu_noise, contact, ranges); they are still read.
inline constexpr const char* kValidationFormat = "stride-validation-2";
/// True for a validation.json object of either format.
bool is_validation_file(const nlohmann::json& doc);
/// The figures the tables show of one entry of validation.json's `worlds`: engine,
/// physics_step_us, contact (the ground's name, "custom" for a calibrated one), the ranges,
/// latency_probability; the entry itself for a stride-validation-1 file, the `world` object as
/// it stands if it cannot be read.
nlohmann::json validation_world_columns(const nlohmann::json& world);
/// The servo and supply draws of a world's columns ("servo friction x0.8-1.6, torque
/// x0.8-1.05, supply 12-16.8 V"), "" for a world without them.
std::string validation_servo_draws_text(const nlohmann::json& columns);

/// Runs every individual in every world and summarises (format kValidationFormat). A
/// missing Ind_O score in the log is computed with task.evaluate().
Status run_validation(const ValidationSubject& subject, const ValidationOptions& options,
                      nlohmann::json& out);

/// Writes `result` as DIR/validation.json (temp file + rename: never half written).
Status write_validation_file(const std::filesystem::path& dir, const nlohmann::json& result);

/// Progress of a validation on stderr: "validate: done/total episodes" redrawn in place on a
/// terminal, else a line at every tenth of the work.
std::function<void(std::size_t, std::size_t)> validation_progress_printer(bool terminal);

/// The human table of a validation result, followed by validation_words.
std::string validation_text(const nlohmann::json& result);

/// A number to two significant digits: 7.5556 -> "7.6", -0.66667 -> "-0.67", 0.96 -> "0.96",
/// 123 -> "120"; "-" for a non-number.
std::string two_significant_digits(const nlohmann::json& value);

/// The gain kept of objective m (0 or 1) of one row of validation.json's flat table, as the
/// tables show it: two significant digits, and "-" unless the run's gain in that objective
/// (run_gain_fM) exceeds the seeds' spread (seed_spread_fM: the larger of Ind_O's and the
/// pick's interquartile range over the world's seeds). A row without the two fields (a file
/// from before they were written) shows the number.
std::string gain_kept_text(const nlohmann::json& row, int m);

/// The same result in plain words: per individual one line saying in which worlds it holds
/// (passes the gate) and where and why it fails (falls, misses the goal, slower than in the
/// run); the pick that holds in most worlds and its front file; what pass and fail mean.
std::string validation_words(const nlohmann::json& result);

}  // namespace stride::opt
