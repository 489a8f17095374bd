// Task configuration: what a robot optimisation (optimiser/configs/*.json) asks for.
//
// A task config names the task (a TaskType: "walk", "walk-omni", "kick", "getup"), the NSGA-II
// inputs (seed, pop, generations, pc, pm, etaC, etaM, seed_fraction), the genome as parameter names
// with bounds and start values (the firmware's current values, Ind_O), the episode settings (the
// task type's own ones parsed by the type: TaskConfig::own, task_settings.hpp) and the
// robust evaluation (trials under seeded randomised worlds, on one or more physics engines,
// aggregated by mean or worst) and the validation that follows a run (`stride validate`,
// validation.hpp). Every error names the offending field, e.g. "genes[3].max: must be greater than
// min".
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/optimiser/nsga2/settings.hpp"
#include "stride/optimiser/tasks/task_settings.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride::opt {

/// One real gene: a firmware parameter and its search interval.
struct TaskGene {
  std::string parameter;  ///< ParameterStore name, e.g. "walk.walk_cycle.zmp_time"
  double min = 0.0;
  double max = 0.0;
  double start = 0.0;  ///< the original value (Ind_O)
};

enum class Aggregate : std::uint8_t { kMean, kWorst };

/// Randomised conditions of robust trials: the world's per-reset ranges (sim::Randomisation,
/// read and written by the world option table's randomisation rows under the same names, ranges
/// and messages) at the trials' defaults, and the IMU noise. The ground (contact_range), the
/// trunk's centre of mass (com_range) and the command latency (latency_probability) are off
/// unless asked for, drawing nothing.
struct TrialRandomisation : sim::Randomisation {
  bool imu_noise = true;
  TrialRandomisation() {
    friction_range = 0.2;
    mass_range = 0.05;
    strength_range = 0.1;
  }
};

/// The physics step of a walk or kick optimisation's trials on Simbody in the faithful world
/// when the config gives none [us] (TaskType::trial_physics_step_us): the largest step at which
/// the faithful robot's results held within the validation gate (tests/bench/RESULTS.md, "The
/// step the model allows": per-direction speeds within the seeds' spread, on every ground and
/// robot variant, time to 2.5 m and the kick within 2 %; 5 ms moved the backward speed by 5 %).
/// The get-up keeps 2000 (at 2500 its front side stood up 3.5 % sooner on Simbody); `stride
/// sim` keeps 2000.
inline constexpr std::int64_t kTrialPhysicsStepUs = 2500;
/// The same on MuJoCo [us]: at 2500 the fast omnidirectional walk (walk-omni-robust.json) fell
/// walking forward in 1-2 of 3 seeds on the soft and hard grounds and two robot variants, where
/// at 2000 it fell nowhere (tests/bench/RESULTS.md). A run whose trials include MuJoCo steps
/// every trial at this step (one step per run: task_trial_step_us).
inline constexpr std::int64_t kTrialPhysicsStepUsMujoco = 2000;

struct TaskConfig {
  std::string task;  ///< a TaskType's name (task_type.hpp): "walk", "walk-omni", "kick", "getup"
  Nsga2Settings settings;
  std::vector<TaskGene> genes;
  // Episode.
  double duration_s = 40.0;  ///< walk: time limit; kick and getup: episode length
  /// The task type's own settings (task_settings.hpp: e.g. WalkSettings, KickSettings), parsed
  /// and written by the type (TaskType::parse_settings, write_settings); none for a task that
  /// has none. own_settings<T>() reads them.
  OwnSettings own;
  /// The task's own settings, which must be a T: T's defaults if the config holds none (one
  /// built in code), a TaskValueTypeError naming both types if it holds another task's.
  template <class T>
  const T& own_settings() const {
    static const T defaults{};
    return own.empty() ? defaults : own.get<T>();
  }
  /// The same, to write (T's defaults first if the config holds none).
  template <class T>
  T& own_settings() {
    return own.as<T>();
  }
  // Robust evaluation.
  int trials = 1;  ///< 1: the nominal world; K > 1: K seeded randomised worlds
  Aggregate aggregate = Aggregate::kMean;
  std::uint64_t trial_seed = 1;  ///< base world seed of the trials
  TrialRandomisation randomisation;
  /// The physics engines every trial runs on (config `engine`: one, or `engines`: a list);
  /// a genome is scored in trials x engines worlds (world k: engine k / trials, trial
  /// k % trials, so both engines see the same seeds).
  std::vector<sim::EngineKind> engines{sim::EngineKind::kSimbody};
  int world_count() const { return trials * static_cast<int>(engines.size()); }
  /// The simulated world every trial and validation world starts from (config `world`: a
  /// named world, a world file's path or object, or an object of the world option table's
  /// fields, sim::WorldSpec; the flat fields `urdf`, `servo_law`, `imu`, `contact` and
  /// `physics_step_us` of before the table still load). Its engine is `engines`; its seed,
  /// noise and randomisation ranges are the trials' (trial_seed, randomisation), so a config
  /// that sets them in `world` is an error naming the field. A relative path (a URDF, a world
  /// file) is relative to the config file. Its physics step, unless the config gives one, is
  /// the task type's trial_physics_step_us() for the run's engines in the faithful world (the
  /// smallest of them: task_trial_step_us; the table's 2000 us in the seed's world or a world
  /// file); run.json always holds the step a run used.
  sim::WorldSpec world;
  /// The step in `world` is the task's default for `engines` (the config gave none): a change
  /// of engines (`stride optimise --engine`) sets it again (apply_task_trial_step). Not in
  /// run.json, which holds the step itself.
  bool trial_step_from_task = false;
  /// Parameter values every episode's firmware takes before the genome (config `params`: a
  /// parameter file's path, relative to the config, or an object {name: number}); genes
  /// override them. Sorted by name. E.g. firmware/config/seed-walk.json with `"world": "seed"`
  /// reproduces the thesis's world and walk.
  std::vector<std::pair<std::string, double>> base_params;
  /// A start genome beside Ind_O (config `starts`, a list; each entry a parameter file's path,
  /// relative to the config, an object {name: number}, or "defaults": the firmware's
  /// registered defaults). A start sets the genes it names, the others keep their `start`
  /// value; names that are not genes are left out (the genome cannot carry them). A value
  /// outside its gene's range is an error (RobotTask::start_genomes). run.json holds the values.
  struct Start {
    bool firmware_defaults = false;
    std::vector<std::pair<std::string, double>> values;  ///< gene values, sorted by name
  };
  std::vector<Start> starts;
  /// `stride validate` after a run (config `validate` {seeds}): fresh seeds per world.
  int validate_seeds = 10;
  // Hypervolume normalisation (ideal and nadir objective vectors).
  std::vector<double> hv_ideal;
  std::vector<double> hv_nadir;
};

/// Parses a task config; the error names the field. A field that is another task's own setting
/// (TaskDescriptor::settings_fields) is an error naming the field and the task it belongs to:
/// "field 'kick_at_s' belongs to task kick, not walk".
Status parse_task_config(const nlohmann::json& doc, TaskConfig& out);
/// Parses the task record of a run's run.json (--resume, stride report, stride validate): as
/// parse_task_config, but other tasks' own settings are left out first. The run.json of a run
/// from before the tasks owned their settings recorded every task's (their defaults, which its
/// task never read); to_json writes the task's own only.
Status parse_task_record(const nlohmann::json& doc, TaskConfig& out);
/// Reads and parses a file; the error names the file and the field.
Status load_task_config(const std::filesystem::path& path, TaskConfig& out);
/// The trials' physics step the config's task type allows on every one of its engines [us]:
/// the smallest of TaskType::trial_physics_step_us over `engines` (kTrialPhysicsStepUs for an
/// unknown task).
std::int64_t task_trial_step_us(const TaskConfig& config);
/// Sets world.physics_step_us to task_trial_step_us() if the step is the task's default
/// (trial_step_from_task), after a change of engines.
void apply_task_trial_step(TaskConfig& config);
/// The config as JSON (recorded in run.json, read back by --resume).
nlohmann::json to_json(const TaskConfig& config);
/// A config's optional finite number `field` into `out` (absent: `out` unchanged); the error
/// names the field. For a task type's own settings (TaskType::parse_settings).
Status read_config_number(const nlohmann::json& doc, const std::string& field, double& out);

}  // namespace stride::opt
