// OwnSettings: what one task type alone reads from its config (the walk's goal and command, the
// kick's script and its moment), parsed from the config's fields by that TaskType
// (TaskType::parse_settings) and written back by it into the task record of run.json
// (TaskType::write_settings). TaskConfig holds them opaque (TaskConfig::own) beside what every task
// shares, so that a run.json holds only its own task's settings. A task's settings are a plain
// struct with a defaulted operator== (compared whole: a field added to it is compared too), held
// as a TaskValue (task_value.hpp: get<T> checked, find<T>, as<T>), the idiom of the figures too.
#pragma once

#include "stride/optimiser/tasks/task_value.hpp"

namespace stride::opt {

struct TaskSettingsKind {
  static constexpr const char* kWhat = "task settings";
  static constexpr bool kComparable = true;
};

/// A task's settings by value (copies copy them), or none.
using OwnSettings = TaskValue<TaskSettingsKind>;

}  // namespace stride::opt
