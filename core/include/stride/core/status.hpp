// Status: success, or a one-line error message naming what was wrong.
//
// Used at start-up and in non-real-time paths (configuration, console, tools) where a bad
// input must be reported clearly and change nothing. Real-time paths do not build Status
// values with messages (that allocates); they report through frames and counters.
#pragma once

#include <string>
#include <utility>

namespace stride {

class [[nodiscard]] Status {
 public:
  Status() = default;  ///< success
  static Status ok() { return {}; }
  static Status error(std::string message) {
    Status s;
    s.failed_ = true;
    s.message_ = std::move(message);
    return s;
  }

  bool is_ok() const noexcept { return !failed_; }
  explicit operator bool() const noexcept { return !failed_; }
  const std::string& message() const noexcept { return message_; }

 private:
  bool failed_ = false;
  std::string message_;
};

}  // namespace stride
