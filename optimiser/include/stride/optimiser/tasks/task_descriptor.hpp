// TaskDescriptor: what a robot optimisation task is, as constants (its name, objectives'
// labels, picks, validation words, constraints, episodes, the ball, its settings' fields), the
// half of a task that is not behaviour (TaskType, task_type.hpp, holds one and adds the
// behaviour). Each task file writes its descriptor once, with designated initialisers, where it
// defines its TaskType; everything that needs a task's constants reads
// `type.descriptor().field`.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "stride/optimiser/tasks/task_config.hpp"
#include "stride/sim_hal/world_options.hpp"

namespace stride::opt {

/// How the validation's plain-language summary names a task's goal and gate measure.
struct ValidationWords {
  std::string reach, reaches, misses, measure;
  std::string motion;           ///< "walk", "kick" or "get-up": what does or does not carry over
  std::string worse;            ///< "{} % slower than in the run": {} is the percentage
  std::string falls = "falls";  ///< "falls in 3 of 10 seeds"
  std::string without_fall = " without a fall";  ///< after `reach` in the gate's legend
};

/// Labels of the two objectives with their units.
struct ObjectiveLabels {
  std::string f1, f2;
};

struct TaskDescriptor {
  /// The config's `task` name.
  std::string_view name;
  /// Constraints of one episode (g >= 0 is feasible).
  int constraint_count = 0;
  /// Labels with units for tables and charts (TaskType::objective_labels gives them, unless the
  /// task names a setting in them, as the walk names its goal).
  ObjectiveLabels labels;
  /// One line for text tables: "f1 time to goal [s], f2 max |a| [m/s^2]".
  std::string legend;
  /// run_pick_names(): the summary keys of the best-f1 and best-f2 front members.
  const char* best_f1_pick = "best_obj1";
  const char* best_f2_pick = "best_obj2";
  /// The validation's plain-language words.
  ValidationWords words;
  /// The objective the validation gate compares with the run (0 or 1).
  int gate_objective = 0;
  /// The ball is on the field.
  bool uses_ball = false;
  /// The run's report and validation show per-direction speeds (direction_speeds.hpp; the
  /// directions from TaskType::direction_segments).
  bool measures_directions = false;
  /// Episodes per world (the get-up: from the front and from the back); their objectives and
  /// constraints are averaged, and a world's score is that average.
  int episodes_per_world = 1;
  /// The physics step of the task's trials in the faithful world when the config gives none,
  /// on Simbody and on MuJoCo [us] (TaskConfig::world): the largest at which the task's results
  /// held there (trial_physics_step_us).
  std::int64_t trial_step_us_simbody = kTrialPhysicsStepUs;
  std::int64_t trial_step_us_mujoco = kTrialPhysicsStepUsMujoco;
  /// The config fields that are the task's own settings (TaskConfig::own): read by
  /// TaskType::parse_settings, written by write_settings, listed by the report; a config that
  /// gives another task's is an error naming the field (parse_task_config).
  std::vector<std::string_view> settings_fields;

  /// The trials' default physics step on `engine` [us].
  std::int64_t trial_physics_step_us(sim::EngineKind engine) const {
    return engine == sim::EngineKind::kMujoco ? trial_step_us_mujoco : trial_step_us_simbody;
  }
  /// Whether `field` is one of settings_fields.
  bool owns_field(std::string_view field) const {
    for (std::string_view own : settings_fields)
      if (own == field) return true;
    return false;
  }
};

}  // namespace stride::opt
