// The task registry and the task's descriptor (task_type.hpp, task_descriptor.hpp): every task
// registered once and found by its descriptor's name, its constants in the descriptor; a task's
// own settings asked for as another task's are an error naming both types (task_value.hpp); a
// config that gives another task's own setting is an error naming the field and its task.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "minimal_task_config.hpp"
#include "stride/optimiser/tasks/kick_settings.hpp"
#include "stride/optimiser/tasks/task_config.hpp"
#include "stride/optimiser/tasks/task_type.hpp"
#include "stride/optimiser/tasks/walk_settings.hpp"
#include "temp_dir.hpp"

namespace stride::opt {
namespace {

TEST(TaskRegistry, EveryTaskIsRegisteredOnceAndFoundByItsDescriptorsName) {
  std::set<std::string_view> names;
  for (const TaskType* type : task_types()) {
    ASSERT_NE(type, nullptr);
    const std::string_view name = type->descriptor().name;
    EXPECT_TRUE(names.insert(name).second) << name << " registered twice";
    EXPECT_EQ(find_task_type(name), type) << name;
  }
  EXPECT_EQ(names, (std::set<std::string_view>{"walk", "walk-omni", "walk-ramp", "walk-command",
                                               "kick", "getup"}));
  EXPECT_EQ(find_task_type("run"), nullptr);
  EXPECT_EQ(find_task_type(""), nullptr);
  EXPECT_EQ(task_type_list(), "walk, walk-omni, walk-ramp, walk-command, kick or getup");
}

TEST(TaskRegistry, TheDescriptorHoldsTheTasksConstants) {
  const TaskDescriptor& walk = find_task_type("walk")->descriptor();
  EXPECT_EQ(walk.constraint_count, 3);
  EXPECT_STREQ(walk.best_f1_pick, "fastest");
  EXPECT_EQ(walk.legend, "f1 time to goal [s], f2 max |a| [m/s^2]");
  EXPECT_EQ(walk.gate_objective, 0);
  EXPECT_FALSE(walk.uses_ball);
  EXPECT_TRUE(walk.owns_field("goal_distance_m"));
  EXPECT_TRUE(walk.owns_field("max_drift_ratio"));
  EXPECT_FALSE(walk.owns_field("kick_at_s"));
  EXPECT_EQ(walk.trial_physics_step_us(sim::EngineKind::kSimbody), kTrialPhysicsStepUs);
  EXPECT_EQ(walk.trial_physics_step_us(sim::EngineKind::kMujoco), kTrialPhysicsStepUsMujoco);
  const TaskDescriptor& kick = find_task_type("kick")->descriptor();
  EXPECT_EQ(kick.gate_objective, 1);
  EXPECT_TRUE(kick.uses_ball);
  EXPECT_EQ(kick.words.motion, "kick");
  const TaskDescriptor& getup = find_task_type("getup")->descriptor();
  EXPECT_EQ(getup.episodes_per_world, 2);
  EXPECT_TRUE(getup.settings_fields.empty());
  EXPECT_EQ(getup.trial_physics_step_us(sim::EngineKind::kSimbody), 2000);
  EXPECT_EQ(find_task_type("walk-ramp")->descriptor().episodes_per_world, 6);
  EXPECT_TRUE(find_task_type("walk-command")->descriptor().measures_directions);
  // The labels are the descriptor's unless the task names a setting in them (the walk's goal).
  EXPECT_EQ(find_task_type("kick")->objective_labels({}).f2, kick.labels.f2);
  EXPECT_EQ(find_task_type("walk")->objective_labels({{"goal_distance_m", 4.0}}).f1,
            "time to 4 m [s]");
}

TEST(TaskRegistry, FieldsAreOwnedByTheirTasks) {
  EXPECT_EQ(tasks_owning_field("kick_at_s"), "task kick");
  EXPECT_EQ(tasks_owning_field("kick_at_s", "kick"), "");
  EXPECT_EQ(tasks_owning_field("max_drift_ratio", "walk"),
            "tasks walk-omni, walk-ramp and walk-command");
  EXPECT_EQ(tasks_owning_field("colour"), "");
}

TEST(TaskSettings, AnotherTasksSettingsAreAnErrorNamingBothTypes) {
  TaskConfig c;
  ASSERT_TRUE(parse_task_config(minimal_task_config(), c));
  EXPECT_EQ(c.own_settings<WalkSettings>().goal_distance_m, 2.5);
  try {
    (void)std::as_const(c).own_settings<KickSettings>();
    ADD_FAILURE() << "a walk's settings read as a kick's";
  } catch (const TaskValueTypeError& e) {
    EXPECT_STREQ(e.what(),
                 "task settings: expected stride::opt::KickSettings, holds "
                 "stride::opt::WalkSettings");
  }
  EXPECT_THROW((void)c.own.get<KickSettings>(), TaskValueTypeError);
  EXPECT_THROW((void)c.own_settings<KickSettings>() /* to write */, TaskValueTypeError);
  EXPECT_EQ(c.own.find<KickSettings>(), nullptr);
  // A config built in code without its settings has its type's defaults.
  const TaskConfig none;
  EXPECT_EQ(none.own_settings<KickSettings>().kick_at_s, KickSettings{}.kick_at_s);
  // Settings compare by type and value.
  TaskConfig d = c;
  EXPECT_TRUE(d.own == c.own);
  d.own_settings<WalkSettings>().walk_vx = 0.5;
  EXPECT_FALSE(d.own == c.own);
  d.own.set(KickSettings{});
  EXPECT_FALSE(d.own == c.own);
  EXPECT_FALSE(OwnSettings{} == c.own);
  EXPECT_TRUE(OwnSettings{} == OwnSettings{});
}

TEST(TaskConfig, AnotherTasksFieldIsAnErrorNamingTheFieldAndItsTask) {
  nlohmann::json doc = minimal_task_config();
  doc["kick_at_s"] = 1.0;
  EXPECT_EQ(parse_error_of(doc), "field 'kick_at_s' belongs to task kick, not walk");
  doc = minimal_task_config();
  doc["task"] = "kick";
  doc["max_drift_ratio"] = 0.1;
  EXPECT_EQ(parse_error_of(doc),
            "field 'max_drift_ratio' belongs to tasks walk, walk-omni, walk-ramp and "
            "walk-command, not kick");
  doc.erase("max_drift_ratio");
  doc["kick_at_s"] = 1.0;  // its own
  EXPECT_EQ(parse_error_of(doc), "ok");
  doc["colour"] = "red";  // nobody's
  EXPECT_EQ(parse_error_of(doc), "colour: unknown field");
  // From a file: the error names the file too.
  const test::TempDir dir;
  nlohmann::json walk = minimal_task_config();
  walk["kick_at_s"] = 1.0;
  const std::filesystem::path file = dir.write("walk.json", walk.dump());
  TaskConfig c;
  const Status s = load_task_config(file, c);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(), file.string() + ": field 'kick_at_s' belongs to task kick, not walk");
  // A run's record (an old run.json held every task's fields) leaves them out.
  ASSERT_TRUE(parse_task_record(walk, c));
  EXPECT_EQ(c.task, "walk");
  EXPECT_EQ(to_json(c).count("kick_at_s"), 0u);  // and is written back without them
}

}  // namespace
}  // namespace stride::opt
