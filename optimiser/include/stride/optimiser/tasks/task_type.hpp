// TaskType: one robot optimisation task (walk, walk-omni, kick, getup), behind one interface and
// found by name. RobotTask runs every task the same way (firmware and world per episode, the
// genome staged and applied at tick 0, trials and engines aggregated); a TaskType says what is
// particular to it:
//   - the episode: how the robot starts (reset_spec), what it is asked to do each tick
//     (TaskEpisode::before_step) and how the finished episode scores (TaskEpisode::score);
//   - the objectives' labels and units, the constraints, the picks' names;
//   - the validation's success test, gate objective and plain-language words;
//   - the report's outcome note;
//   - its own settings (TaskConfig::own): their config fields, read and written by the type;
//   - its own figures of an episode (EpisodeScore::figures, task_figures.hpp): written by its
//     episode, merged over a world's episodes and shown in the validation by the type.
// A new task is one file that defines a TaskType, one line in task_registry.cpp and a config.
//
// Real-time rule: before_step runs inside the lockstep episode, once per 10 ms control tick; it
// reads the world and requests motions, and allocates nothing. Everything else runs outside it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/firmware/controller.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/hal/sensor_frame.hpp"
#include "stride/optimiser/tasks/episode_score.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
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

/// How the validation's plain-language summary names a task's goal and gate measure.
struct ValidationWords {
  std::string reach, reaches, misses, measure;
  std::string motion;           ///< "walk", "kick" or "get-up": what does or does not carry over
  std::string worse;            ///< "{} % slower than in the run": {} is the percentage
  std::string falls = "falls";  ///< "falls in 3 of 10 seeds"
  std::string without_fall = " without a fall";  ///< after `reach` in the gate's legend
};

/// A task's own figures of one individual in one validation world, over its seeds: fields the
/// task adds to the world's cell in validation.json (`cell`) and to the row of its flat table
/// (`table_row`).
struct ValidationFigures {
  nlohmann::json cell = nlohmann::json::object();
  nlohmann::json table_row = nlohmann::json::object();
};

/// Labels of the two objectives with their units.
struct ObjectiveLabels {
  std::string f1, f2;
};

class TaskType {
 public:
  virtual ~TaskType() = default;
  /// The config's `task` name.
  virtual std::string_view name() const = 0;
  /// Constraints of one episode (g >= 0 is feasible).
  virtual int constraint_count() const = 0;
  /// Labels with units for tables and charts; `task_doc` is the config as recorded in run.json
  /// (a label may name a setting, e.g. the goal distance).
  virtual ObjectiveLabels objective_labels(const nlohmann::json& task_doc) const = 0;
  /// One line for text tables: "f1 time to goal [s], f2 max |a| [m/s^2]".
  virtual std::string objective_legend() const = 0;
  /// run_pick_names(): the summary keys of the best-f1 and best-f2 front members.
  virtual const char* best_f1_pick() const = 0;
  virtual const char* best_f2_pick() const = 0;
  virtual ValidationWords validation_words() const = 0;
  /// The objective the validation gate compares with the run (0 or 1).
  virtual int gate_objective() const { return 0; }
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
  /// The ball is on the field.
  virtual bool uses_ball() const { return false; }
  /// The run's report and validation show per-direction speeds (direction_speeds.hpp).
  virtual bool measures_directions() const { return false; }
  /// The six directions of an episode's figures, for a task that measures_directions(): what
  /// the report's per-direction table reads. By default the figures' DirectionFigures
  /// (direction_figures.hpp).
  virtual OmniSegments direction_segments(const EpisodeScore& score) const;
  /// Episodes per world (the get-up: from the front and from the back); their objectives and
  /// constraints are averaged, and a world's score is that average.
  virtual int episodes_per_world() const { return 1; }
  /// The physics step of the task's trials on `engine` in the faithful world when the config
  /// gives none [us] (TaskConfig::world): the largest at which the task's results held there.
  virtual std::int64_t trial_physics_step_us(sim::EngineKind engine) const {
    return engine == sim::EngineKind::kMujoco ? kTrialPhysicsStepUsMujoco : kTrialPhysicsStepUs;
  }
  /// How episode `episode` of a world starts (default: standing, the ball before the right foot).
  virtual sim::ResetSpec reset_spec(const TaskConfig& config, int episode) const;
  /// The config fields that are the task's own settings (TaskConfig::own): read by
  /// parse_settings, written by write_settings, listed by the report.
  virtual std::vector<std::string_view> settings_fields() const { return {}; }
  /// Reads the task's own settings from the config's fields into `out` (`config`: the shared
  /// part, already read); the error names the field. Fields of other tasks are left alone.
  virtual Status parse_settings(const nlohmann::json& /*doc*/, const TaskConfig& /*config*/,
                                OwnSettings& /*out*/) const {
    return {};
  }
  /// Writes the task's own settings as the config's fields into the task record `doc`.
  virtual void write_settings(const TaskConfig& /*config*/, nlohmann::json& /*doc*/) const {}
  /// When the task's action starts [s] (the kick: kick_at_s), where the report's strip of a
  /// ball task begins looking for the ball's motion.
  virtual double action_at_s(const TaskConfig& /*config*/) const { return 0.0; }
  /// Checks the config's task-specific settings beyond what parse_task_config checks.
  virtual Status check(const TaskConfig& config) const;
  /// The episode, once the world is reset (its start state readable in `world`).
  virtual std::unique_ptr<TaskEpisode> start_episode(const TaskConfig& config, int episode,
                                                     double period_s,
                                                     const sim::SimWorld& world) const = 0;
};

/// The outcome note of a walking task: "fell at 3.20 s", or "1.52 m in 20 s, goal not reached".
std::string travel_note(bool fell, double distance_m, double end_s);

/// The task named `name`, or null.
const TaskType* find_task_type(std::string_view name);
/// "walk, walk-omni, kick or getup": for error messages.
std::string task_type_list();
/// Whether `field` is one of some task type's own settings (settings_fields()): a config (an
/// old run.json holds every task's) may give it for another task.
bool is_task_settings_field(std::string_view field);

}  // namespace stride::opt
