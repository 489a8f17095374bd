// TaskType: one robot optimisation task (walk, walk-omni, walk-ramp, walk-command, kick, getup),
// a constant descriptor plus its behaviour, behind one interface and found by name. RobotTask
// runs every task the same way (firmware and world per episode, the genome staged and applied at
// tick 0, trials and engines aggregated); a task says what is particular to it:
//   - as constants, its TaskDescriptor (task_descriptor.hpp: name, constraints, objectives'
//     labels and legend, picks, validation words and gate objective, the ball, the directions,
//     episodes per world, the trials' physics step, its settings' fields), given to TaskType's
//     constructor and read through descriptor();
//   - as behaviour, the virtuals here: the episode (start_episode: how it asks and scores;
//     reset_spec: how the robot starts), the validation's success test (succeeded), the
//     report's outcome note, replay goal and action moment, the merge and validation of its own
//     figures, its own settings (parse_settings, write_settings, check) and the labels when a
//     setting is named in them.
// Its own settings (TaskConfig::own, task_settings.hpp) and its own figures of an episode
// (EpisodeScore::figures, task_figures.hpp) are one idiom, TaskValue (task_value.hpp): its
// plain struct by value, asked for by type (get<T> checked).
// A new task is one file that defines a TaskType and `const TaskType& <id>_task_type()`, one
// line in task_registry.cpp's table (STRIDE_TASK_TYPES) and a config.
//
// Real-time rule: before_step runs inside the lockstep episode, once per 10 ms control tick; it
// reads the world and requests motions, and allocates nothing. Everything else runs outside it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/firmware/controller.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/hal/sensor_frame.hpp"
#include "stride/optimiser/tasks/episode_score.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
#include "stride/optimiser/tasks/task_descriptor.hpp"
#include "stride/optimiser/tasks/walk_measures.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::opt {

/// One episode of a task, made by TaskType::start_episode after the world is reset.
class TaskEpisode {
 public:
  virtual ~TaskEpisode() = default;
  /// Length, goal and stop rules of the episode (sim::run_episode).
  virtual sim::EpisodeOptions options() const = 0;
  /// Once, at the first tick, after the genome is applied and before the first before_step: the
  /// firmware's parameters as the episode runs with them (for a task whose requests depend on
  /// them; outside the real-time rule).
  virtual void parameters_applied(const fw::ParameterStore& /*params*/) {}
  /// Every tick, after the genome is applied and before Controller::step: the task's requests
  /// (real-time: no allocation, no I/O).
  virtual void before_step(const hal::SensorFrame& sensors, hal::Tick tick,
                           const sim::SimWorld& world, fw::Controller& controller) = 0;
  /// Every tick, after Controller::step, with the world its sensors came from (real-time, as
  /// before_step): what the task follows.
  virtual void after_step(const fw::Controller& /*controller*/, const sim::SimWorld& /*world*/,
                          hal::Tick /*tick*/) {}
  /// The finished episode's objectives, constraints and figures (the shared ones are filled; the
  /// task writes its own in `out.figures`); `result` already counts a
  /// failed world as a fall at that moment. An error names what went wrong (a refused request).
  virtual Status score(const sim::EpisodeResult& result, const sim::SimWorld& world,
                       const fw::Controller& controller, EpisodeScore& out) = 0;
};

/// A task's own figures of one individual in one validation world, over its seeds: fields the
/// task adds to the world's cell in validation.json (`cell`) and to the row of its flat table
/// (`table_row`).
struct ValidationFigures {
  nlohmann::json cell = nlohmann::json::object();
  nlohmann::json table_row = nlohmann::json::object();
};

class TaskType {
 public:
  explicit TaskType(TaskDescriptor descriptor) : descriptor_(std::move(descriptor)) {}
  virtual ~TaskType() = default;
  TaskType(const TaskType&) = delete;
  TaskType& operator=(const TaskType&) = delete;

  /// What the task is, as constants.
  const TaskDescriptor& descriptor() const { return descriptor_; }

  /// Labels with units for tables and charts; `task_doc` is the config as recorded in run.json
  /// (a label may name a setting, e.g. the goal distance). By default the descriptor's.
  virtual ObjectiveLabels objective_labels(const nlohmann::json& /*task_doc*/) const {
    return descriptor_.labels;
  }
  /// A validation episode that neither fell nor failed: did it do what the task asks?
  virtual bool succeeded(const TaskConfig& config, const EpisodeScore& score) const = 0;
  /// The report's one-line outcome of a replayed episode that ended at `end_s` (by default
  /// whether it fell).
  virtual std::string outcome_note(const TaskConfig& config, const EpisodeScore& score,
                                   double end_s) const;
  /// Folds the task's own figures of episode `count` (1-based, > 1) of a world into the world's
  /// figures so far (RobotTask merges the shared ones). By default the first episode's stand for
  /// the world.
  virtual void merge_figures(const TaskFigures& /*next*/, int /*count*/,
                             TaskFigures& /*total*/) const {}
  /// The task's own figures over one world's validation seeds (in seed order; none by default).
  virtual ValidationFigures validation_figures(
      const std::vector<const EpisodeScore*>& /*seeds*/) const {
    return {};
  }
  /// The goal line the report's replay draws [m from the start] (none by default).
  virtual std::optional<double> replay_goal_m(const TaskConfig& /*config*/) const {
    return std::nullopt;
  }
  /// When the task's action starts [s] (the kick: kick_at_s), where the report's strip of a
  /// ball task begins looking for the ball's motion.
  virtual double action_at_s(const TaskConfig& /*config*/) const { return 0.0; }
  /// The six directions of an episode's figures, for a task that measures_directions: what
  /// the report's per-direction table reads. By default the figures' DirectionFigures
  /// (direction_figures.hpp).
  virtual OmniSegments direction_segments(const EpisodeScore& score) const;
  /// How episode `episode` of a world starts (default: standing, the ball before the right foot).
  virtual sim::ResetSpec reset_spec(const TaskConfig& config, int episode) const;
  /// Reads the task's own settings (descriptor().settings_fields) from the config's fields into
  /// `out` (`config`: the shared part, already read); the error names the field.
  virtual Status parse_settings(const nlohmann::json& /*doc*/, const TaskConfig& /*config*/,
                                OwnSettings& /*out*/) const {
    return {};
  }
  /// Writes the task's own settings as the config's fields into the task record `doc`.
  virtual void write_settings(const TaskConfig& /*config*/, nlohmann::json& /*doc*/) const {}
  /// Checks the config's task-specific settings beyond what parse_task_config checks.
  virtual Status check(const TaskConfig& /*config*/) const { return {}; }
  /// The episode, once the world is reset (its start state readable in `world`).
  virtual std::unique_ptr<TaskEpisode> start_episode(const TaskConfig& config, int episode,
                                                     double period_s,
                                                     const sim::SimWorld& world) const = 0;

 private:
  const TaskDescriptor descriptor_;
};

/// The outcome note of a walking task: "fell at 3.20 s", or "1.52 m in 20 s, goal not reached".
std::string travel_note(bool fell, double distance_m, double end_s);

/// The task named `name`, or null.
const TaskType* find_task_type(std::string_view name);
/// Every registered task, in the registry's order (task_registry.cpp).
const std::vector<const TaskType*>& task_types();
/// "walk, walk-omni, kick or getup": for error messages.
std::string task_type_list();
/// The tasks other than `task` whose own settings (TaskDescriptor::settings_fields) include
/// `field`, as "task kick" or "tasks walk, walk-omni and walk-ramp"; empty when none.
std::string tasks_owning_field(std::string_view field, std::string_view task = {});

}  // namespace stride::opt
