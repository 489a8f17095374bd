// ParameterStore: every tunable value of the firmware, typed, bounded and documented.
//
// Modules register their parameters at start-up (add) and keep the returned handle; the
// control thread reads values by handle (value(), O(1), no allocation). Writers (console,
// optimiser, files) never change live values directly: they stage a validated batch, and the
// control loop applies everything staged at the start of the next tick (apply_staged), so a
// batch (a genome, a parameter file) is applied in one tick or not at all.
//
// Every write is validated against the parameter's type, bounds and flags; a bad write gets a
// one-line error naming the parameter and the allowed range, and changes nothing.
//
// Thread rules: add() and the load/save helpers before the loop starts or off the control
// thread; stage()/set_* from any one non-real-time thread at a time; apply_staged() and
// value() from the control thread (apply_staged never blocks: it try-locks and otherwise
// applies at the following tick).
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "stride/core/status.hpp"

namespace stride::fw {

enum class ParamType : std::uint8_t { kReal, kInt, kBool };

/// Text name of a type ("real", "int", "bool").
std::string_view to_string(ParamType type);

struct ParamSpec {
  std::string name;  ///< dotted name, e.g. "walk.step_time"
  ParamType type = ParamType::kReal;
  double default_value = 0.0;
  double min = 0.0;            ///< inclusive lower bound (bool: 0)
  double max = 0.0;            ///< inclusive upper bound (bool: 1)
  std::string unit;            ///< SI unit or "" (e.g. "s", "m", "rad", "1")
  std::string description;     ///< one line
  bool read_only = false;      ///< cannot be written after registration (only by defaults)
  bool needs_restart = false;  ///< written values take effect after a restart of stride-fw
};

/// Handle of a registered parameter: stable for the store's lifetime.
using ParamHandle = std::uint32_t;

/// One write of a batch: parameter name and new value (bool as 0/1).
using ParamWrite = std::pair<std::string, double>;

/// Told by apply_staged() about each live value it changes (the flight recorder logs them).
/// Called on the control thread: implementations must not block, allocate or throw.
class ParamChangeSink {
 public:
  virtual void on_param_change(ParamHandle handle, double value) noexcept = 0;
  virtual ~ParamChangeSink() = default;
};

class ParameterStore {
 public:
  ParameterStore() = default;
  ParameterStore(const ParameterStore&) = delete;
  ParameterStore& operator=(const ParameterStore&) = delete;

  /// Registers a parameter (start-up only). Throws std::invalid_argument naming the problem
  /// for a duplicate or empty name, min > max, a default outside the bounds, or a non-integral
  /// int default.
  ParamHandle add(ParamSpec spec);

  /// Convenience for add() of a real parameter.
  ParamHandle add_real(std::string name, double default_value, double min, double max,
                       std::string unit, std::string description);

  std::size_t size() const noexcept { return specs_.size(); }
  std::optional<ParamHandle> find(std::string_view name) const;
  const ParamSpec& spec(ParamHandle handle) const { return specs_.at(handle); }

  /// Live value. Real-time: yes.
  double value(ParamHandle handle) const noexcept {
    return live_[handle].load(std::memory_order_relaxed);
  }
  /// Live value by name; an error names an unknown parameter.
  Status get(std::string_view name, double& out) const;

  /// Checks one write without doing it: unknown name, read-only, non-finite, wrong type
  /// (int must be integral, bool 0 or 1), or outside [min, max]. The message names the
  /// parameter and the allowed range.
  Status check(std::string_view name, double value) const;

  /// Validates the whole batch, then stages all of it, or nothing if any write is bad.
  /// Applied by the next apply_staged().
  Status stage(const std::vector<ParamWrite>& batch);
  Status stage(std::string_view name, double value);

  /// Applies everything staged since the last call, atomically. Returns true if values
  /// changed. Real-time: yes (no allocation, never blocks; if a writer holds the lock the
  /// batch is applied at the next call). `changes`, if given, hears of every value written.
  bool apply_staged(ParamChangeSink* changes = nullptr) noexcept;
  /// True while a staged batch waits for apply_staged().
  bool has_staged() const;
  /// Number of batches applied since construction (for tests and the console's status).
  std::uint64_t applied_batches() const noexcept { return applied_batches_; }

  /// Applies a batch immediately (validated, all or nothing). For start-up and tools that
  /// own the store while no loop runs; never call it while a loop is running.
  Status set_now(const std::vector<ParamWrite>& batch);

  /// Restores every writable parameter to its default (staged, like any write).
  Status stage_defaults();

  /// Names in registration order whose name starts with `prefix` ("" for all).
  std::vector<ParamHandle> list(std::string_view prefix = {}) const;

  // --- JSON ------------------------------------------------------------------------------
  // A parameter file is a JSON object {"name": value, ...}; nested objects are flattened with
  // dots ({"walk": {"step_time": 0.85}} is "walk.step_time"). Values are numbers or booleans.

  /// Parses a parameter file into a batch and validates all of it against this store. The
  /// error names the file, the parameter and what is wrong.
  Status parse_json_file(const std::filesystem::path& path, std::vector<ParamWrite>& out) const;
  Status parse_json(const nlohmann::json& doc, std::vector<ParamWrite>& out,
                    std::string_view origin = "parameters") const;

  /// Loads a file and applies it now (set_now) or stages it (stage); all or nothing.
  Status load_file_now(const std::filesystem::path& path);
  Status stage_file(const std::filesystem::path& path);

  /// The live values as a flat JSON object (name -> value; bools as true/false).
  nlohmann::json to_json(std::string_view prefix = {}) const;
  /// Full description of every parameter (for `list --json` and documentation).
  nlohmann::json describe_json(std::string_view prefix = {}) const;

  /// Writes to_json() to `path` atomically (temporary file in the same folder, then rename).
  Status save_file(const std::filesystem::path& path, std::string_view prefix = {}) const;

 private:
  Status validate(ParamHandle handle, double value) const;

  std::vector<ParamSpec> specs_;
  std::map<std::string, ParamHandle, std::less<>> index_;
  // Live values: written by the control thread (apply_staged), read by any thread (console
  // status, save). Relaxed atomics make those reads race-free at no cost on x86-64 and
  // aarch64; a deque never moves its elements when add() appends at start-up.
  std::deque<std::atomic<double>> live_;
  // Staging area, preallocated at registration so apply_staged never allocates.
  mutable std::mutex staging_mutex_;
  std::vector<double> staged_values_;
  std::vector<std::uint8_t> staged_dirty_;
  bool staged_pending_ = false;
  std::uint64_t applied_batches_ = 0;
};

/// Formats a double compactly for messages ("0.85", "1e-05").
std::string format_number(double value);

}  // namespace stride::fw
