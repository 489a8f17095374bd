// TaskSettings: what one task type alone reads from its config (the walk's goal and command, the
// kick's script and its moment), parsed from the config's fields by that TaskType
// (TaskType::parse_settings) and written back by it into the task record of run.json
// (TaskType::write_settings). TaskConfig holds them opaque (TaskConfig::own) beside what every task
// shares, so that a run.json holds only its own task's settings. A task's settings are a plain
// struct with a defaulted operator== (compared whole: a field added to it is compared too).
#pragma once

#include <memory>
#include <utility>

namespace stride::opt {

class TaskSettings {
 public:
  virtual ~TaskSettings() = default;
  virtual std::unique_ptr<TaskSettings> clone() const = 0;
  virtual bool equals(const TaskSettings& other) const = 0;
};

/// A task's settings struct T as TaskSettings.
template <class T>
class SettingsOf final : public TaskSettings {
 public:
  explicit SettingsOf(T v) : value(std::move(v)) {}
  std::unique_ptr<TaskSettings> clone() const override {
    return std::make_unique<SettingsOf>(*this);
  }
  bool equals(const TaskSettings& other) const override {
    const auto* o = dynamic_cast<const SettingsOf*>(&other);
    return o != nullptr && o->value == value;
  }
  T value;
};

/// A task's settings by value (copies copy them), or none.
class OwnSettings {
 public:
  OwnSettings() = default;
  OwnSettings(const OwnSettings& o) : p_(o.p_ ? o.p_->clone() : nullptr) {}
  OwnSettings(OwnSettings&&) noexcept = default;
  OwnSettings& operator=(const OwnSettings& o) {
    if (this != &o) p_ = o.p_ ? o.p_->clone() : nullptr;
    return *this;
  }
  OwnSettings& operator=(OwnSettings&&) noexcept = default;
  ~OwnSettings() = default;

  /// The settings if they are a T, else null.
  template <class T>
  const T* get() const {
    const auto* s = dynamic_cast<const SettingsOf<T>*>(p_.get());
    return s != nullptr ? &s->value : nullptr;
  }
  /// The settings as a T; T's defaults first if they are none or of another type.
  template <class T>
  T& as() {
    if (get<T>() == nullptr) p_ = std::make_unique<SettingsOf<T>>(T{});
    return static_cast<SettingsOf<T>&>(*p_).value;
  }
  bool empty() const { return p_ == nullptr; }
  bool operator==(const OwnSettings& o) const {
    return p_ == nullptr ? o.p_ == nullptr : o.p_ != nullptr && p_->equals(*o.p_);
  }

 private:
  std::unique_ptr<TaskSettings> p_;
};

}  // namespace stride::opt
