// TaskFigures: the figures that one task type alone keeps of an episode (the walk's time to the
// goal, the kick's ball distance, the get-up's episodes stood, the walking directions' speeds),
// beside what every task shares in EpisodeScore. The task's episode writes them
// (TaskEpisode::score), its type merges them over a world's episodes (TaskType::merge_figures)
// and shows them (outcome notes, validation figures). A task's figures are a plain copyable
// struct in its own header (walk_figures.hpp, ...), held as a TaskValue (task_value.hpp), the
// idiom of the settings too: readers ask for the task's struct by type (get<T> checked: another
// type is an error naming both; read<T>: T's defaults when there are none), so a wrong guess is
// seen, not misread.
#pragma once

#include "stride/optimiser/tasks/task_value.hpp"

namespace stride::opt {

struct TaskFiguresKind {
  static constexpr const char* kWhat = "task figures";
  static constexpr bool kComparable = false;
};

/// A task's figures of an episode by value, or none.
using TaskFigures = TaskValue<TaskFiguresKind>;

}  // namespace stride::opt
