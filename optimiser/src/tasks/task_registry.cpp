// The robot tasks by name, and TaskType's defaults (see task_type.hpp).
//
// Registering a task is one line in STRIDE_TASK_TYPES: TASK(id) declares `const TaskType&
// id_task_type()`, which the task's file defines, and lists it in the table, in the order
// task_type_list() names them. (One table rather than self-registering objects in the task
// files: the linker leaves out of a static library a file nothing refers to.)
#include <cmath>
#include <cstdio>

#include "stride/optimiser/tasks/task_type.hpp"

// clang-format off
#define STRIDE_TASK_TYPES(TASK) \
  TASK(walk)                    \
  TASK(walk_omni)               \
  TASK(walk_ramp)               \
  TASK(walk_command)            \
  TASK(kick)                    \
  TASK(getup)
// clang-format on

namespace stride::opt {

#define STRIDE_DECLARE_TASK(id) const TaskType& id##_task_type();
STRIDE_TASK_TYPES(STRIDE_DECLARE_TASK)
#undef STRIDE_DECLARE_TASK

const std::vector<const TaskType*>& task_types() {
#define STRIDE_LIST_TASK(id) &id##_task_type(),
  static const std::vector<const TaskType*> types = {STRIDE_TASK_TYPES(STRIDE_LIST_TASK)};
#undef STRIDE_LIST_TASK
  return types;
}

const TaskType* find_task_type(std::string_view name) {
  for (const TaskType* type : task_types())
    if (type->descriptor().name == name) return type;
  return nullptr;
}

namespace {

/// "a", "a or b", "a, b or c" (`last`: "or", "and").
std::string word_list(const std::vector<std::string_view>& words, const char* last) {
  std::string list;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0) list += i + 1 == words.size() ? std::string(" ") + last + " " : ", ";
    list += words[i];
  }
  return list;
}

}  // namespace

std::string task_type_list() {
  std::vector<std::string_view> names;
  for (const TaskType* type : task_types()) names.push_back(type->descriptor().name);
  return word_list(names, "or");
}

std::string tasks_owning_field(std::string_view field, std::string_view task) {
  std::vector<std::string_view> owners;
  for (const TaskType* type : task_types())
    if (type->descriptor().name != task && type->descriptor().owns_field(field))
      owners.push_back(type->descriptor().name);
  if (owners.empty()) return "";
  return (owners.size() == 1 ? "task " : "tasks ") + word_list(owners, "and");
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

}  // namespace stride::opt
