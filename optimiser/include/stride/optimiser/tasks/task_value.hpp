// TaskValue: what one task type alone keeps, held by value beside what every task shares, its
// type erased. The one idiom of a task's own settings (OwnSettings, TaskConfig::own,
// task_settings.hpp) and of its own figures of an episode (TaskFigures, EpisodeScore::figures,
// task_figures.hpp): a task's plain copyable struct (WalkSettings, KickFigures, ...) in a
// std::any, asked for by type.
//   - get<T>(): the value, which must be a T: held as anything else (or nothing), it throws
//     TaskValueTypeError naming the type expected and the type held (a programming error, never
//     undefined behaviour or a silent default);
//   - find<T>(): the value if it is a T, else null (for a reader that may meet none);
//   - read<T>(): the value as a T, or T's defaults if it holds none (a test's score, a failed
//     set-up's); held as another type, it throws as get<T>() does;
//   - as<T>(): the value as a T, to write; T's defaults first if it holds none; held as another
//     type, it throws as get<T>() does.
// Kind names what the values are in the error ("task settings", "task figures") and whether they
// compare (Kind::kComparable: the settings do, each struct with an operator==, checked here).
//
// Type-erased rather than a std::variant of every task's struct: a new task adds its struct and
// nothing here.
#pragma once

#include <any>
#include <concepts>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <utility>

namespace stride::opt {

/// A TaskValue asked for as a type it does not hold: names both.
class TaskValueTypeError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// A type's readable name ("stride::opt::WalkSettings"), for TaskValueTypeError.
std::string task_value_type_name(const std::type_info& type);

template <class Kind>
class TaskValue {
 public:
  /// The value, which must be a T; else TaskValueTypeError names both types.
  template <class T>
  const T& get() const {
    if (const T* v = find<T>()) return *v;
    throw mismatch(typeid(T));
  }
  template <class T>
  T& get() {
    return const_cast<T&>(static_cast<const TaskValue&>(*this).get<T>());
  }
  /// The value if it is a T, else null.
  template <class T>
  const T* find() const {
    return std::any_cast<T>(&value_);
  }
  /// The value as a T, or T's defaults if it holds none; another type is a TaskValueTypeError.
  template <class T>
  T read() const {
    return empty() ? T{} : get<T>();
  }
  /// The value as a T, to write: T's defaults first if it holds none; another type is a
  /// TaskValueTypeError.
  template <class T>
  T& as() {
    if (empty()) set(T{});
    return get<T>();
  }
  /// Holds `value` (whatever it held before).
  template <class T>
  void set(T value) {
    if constexpr (Kind::kComparable) {
      static_assert(std::equality_comparable<T>, "a task's settings struct needs an operator==");
      equal_ = [](const std::any& a, const std::any& b) {
        return *std::any_cast<T>(&a) == *std::any_cast<T>(&b);
      };
    }
    value_ = std::move(value);
  }
  bool empty() const { return !value_.has_value(); }
  /// The held type's name ("none" when empty).
  std::string held_type() const { return empty() ? "none" : task_value_type_name(value_.type()); }
  /// Both hold nothing, or the same type and equal values (Kind::kComparable only).
  bool operator==(const TaskValue& o) const requires Kind::kComparable {
    if (empty() || o.empty()) return empty() == o.empty();
    return value_.type() == o.value_.type() && equal_(value_, o.value_);
  }

 private:
  TaskValueTypeError mismatch(const std::type_info& expected) const {
    return TaskValueTypeError(std::string(Kind::kWhat) + ": expected " +
                              task_value_type_name(expected) + ", holds " + held_type());
  }

  std::any value_;
  bool (*equal_)(const std::any&, const std::any&) = nullptr;
};

}  // namespace stride::opt
