// The robot tasks by name, and TaskType's defaults (see task_type.hpp). A new task adds its
// file and one line to kTasks.
#include <array>
#include <cmath>
#include <cstdio>

#include "stride/optimiser/tasks/task_type.hpp"

namespace stride::opt {

const TaskType& walk_task_type();
const TaskType& walk_omni_task_type();
const TaskType& kick_task_type();
const TaskType& getup_task_type();
const TaskType& walk_ramp_task_type();
const TaskType& walk_command_task_type();

namespace {

using TaskTypeGetter = const TaskType& (*)();
constexpr std::array<TaskTypeGetter, 6> kTasks = {&walk_task_type,      &walk_omni_task_type,
                                                  &walk_ramp_task_type, &walk_command_task_type,
                                                  &kick_task_type,      &getup_task_type};

}  // namespace

const TaskType* find_task_type(std::string_view name) {
  for (TaskTypeGetter get : kTasks)
    if (get().name() == name) return &get();
  return nullptr;
}

std::string task_type_list() {
  std::string list;
  for (std::size_t i = 0; i < kTasks.size(); ++i) {
    if (i > 0) list += i + 1 == kTasks.size() ? " or " : ", ";
    list += kTasks[i]().name();
  }
  return list;
}

bool is_task_settings_field(std::string_view field) {
  for (TaskTypeGetter get : kTasks)
    for (std::string_view own : get().settings_fields())
      if (own == field) return true;
  return false;
}

std::string travel_note(bool fell, double distance_m, double end_s) {
  char text[160];
  if (fell)
    std::snprintf(text, sizeof text, "fell at %.2f s", end_s);
  else
    std::snprintf(text, sizeof text, "%.2f m in %.3g s, goal not reached", distance_m, end_s);
  return text;
}

std::string TaskType::outcome_note(const TaskConfig&, const EpisodeScore& s, double end_s) const {
  char text[64];
  std::snprintf(text, sizeof text, s.fell ? "fell at %.2f s" : "ended at %.2f s", end_s);
  return text;
}

sim::ResetSpec TaskType::reset_spec(const TaskConfig&, int) const {
  sim::ResetSpec spec = sim::ResetSpec::standing();
  spec.ball_position = {0.25, -0.06, std::nan("")};  // in front of the right (kicking) foot
  return spec;
}

Status TaskType::check(const TaskConfig&) const {
  return {};
}

}  // namespace stride::opt
