// TaskFigures: the figures that one task type alone keeps of an episode (the walk's time to the
// goal, the kick's ball distance, the get-up's episodes stood, the walking directions' speeds),
// beside what every task shares in EpisodeScore. The task's episode writes them
// (TaskEpisode::score), its type merges them over a world's episodes (TaskType::merge_figures)
// and shows them (outcome notes, validation figures); readers ask for the task's figures struct
// by type (get<T>: null when the figures are not a T), so a wrong guess is seen, not misread.
// A task's figures are a plain copyable struct in its own header (walk_figures.hpp, ...).
//
// Type-erased (std::any) rather than a variant of every task's struct: a new task adds its
// struct and nothing here.
#pragma once

#include <any>

namespace stride::opt {

class TaskFigures {
 public:
  /// The figures if they are a T, else null.
  template <class T>
  const T* get() const {
    return std::any_cast<T>(&value_);
  }
  /// The figures as a T, to write; T's defaults first if they are none or of another type.
  template <class T>
  T& as() {
    if (get<T>() == nullptr) value_ = T{};
    return *std::any_cast<T>(&value_);
  }
  /// The figures as a T, or T's defaults (nothing reached, nothing measured) if they are none
  /// or of another type: for readers that judge a score whatever its origin (a test's, a failed
  /// set-up's).
  template <class T>
  T read() const {
    const T* figures = get<T>();
    return figures != nullptr ? *figures : T{};
  }
  bool empty() const { return !value_.has_value(); }

 private:
  std::any value_;
};

}  // namespace stride::opt
