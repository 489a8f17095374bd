// CommandInterpreter: executes one console command line against the live firmware and returns
// the reply (reply.hpp). Commands (firmware/console/README.md has the full reference):
//
//   help                         list the commands
//   list [prefix]                every parameter (value, unit, type, bounds, flags)
//   get NAME                     one value: `ok NAME = VALUE`
//   set NAME VALUE               validated, staged, applied at the next tick
//   reset NAME|all               back to the default(s)
//   save [FILE]                  live values to a JSON file, atomically
//   load [FILE]                  a parameter file, validated as a whole, then applied in one tick
//   flash JSON                   a whole parameter file sent as one line of JSON, same rules
//   status                       motion state, loop statistics, bus health, servos
//   torque on|off [force]        servo torque
//   walk VX VY VTHETA            walk with normalised velocities in [-1, 1]
//   stop                         stop walking or playing, and stand
//   script NAME                  play a keyframe script
//
// Every parameter change goes through ParameterStore::stage (all or nothing, applied by the
// control loop at its next tick); the interpreter then waits up to apply_timeout for the loop
// to take it, so a following `get` reads the new value. Safety rules: motion_guard.hpp.
// A write to a needs-restart parameter is accepted and stored, and the reply says it takes
// effect after a restart (save, then restart stride-fw).
//
// Thread rules: runs on the console thread; never on the control thread.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "stride/firmware/console/motion_guard.hpp"
#include "stride/firmware/console/reply.hpp"
#include "stride/firmware/controller.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/servo_table.hpp"

namespace stride::fw::console {

struct ConsoleContext {
  ParameterStore* params = nullptr;
  Controller* controller = nullptr;
  const ServoTable* servos = nullptr;  ///< names in `status` (optional)
  /// File of `save` and `load` without an argument.
  std::filesystem::path default_file = "stride-params.json";
  /// Extra `status` lines about the loop and the bus (optional; stride-fw supplies them).
  std::function<std::vector<std::string>()> loop_status;
  /// How long a change may wait for the loop to apply it before the reply is sent anyway.
  std::chrono::milliseconds apply_timeout{1000};
};

class CommandInterpreter {
 public:
  /// `context.params` and `context.controller` must be set and outlive the interpreter.
  explicit CommandInterpreter(ConsoleContext context);

  Reply execute(std::string_view line);

  /// A walk was requested and not stopped (part of "moving", motion_guard.hpp).
  bool walk_requested() const noexcept { return walk_requested_; }
  MotionSituation situation() const;

 private:
  using Args = std::vector<std::string>;
  Reply help() const;
  Reply list(const Args& args) const;
  Reply get(const Args& args) const;
  Reply set(const Args& args);
  Reply reset(const Args& args);
  Reply save(const Args& args) const;
  Reply load(const Args& args);
  Reply flash(std::string_view json);
  Reply status() const;
  Reply torque(const Args& args);
  Reply walk(const Args& args);
  Reply stop();
  Reply script(const Args& args);

  /// Guard, stage and wait for the loop: the common tail of set/reset/load/flash.
  Reply stage_batch(const std::vector<ParamWrite>& batch, std::string done_text);
  /// Waits (up to apply_timeout) until the controller reports the torque state `on`.
  bool wait_for_torque(bool on) const;
  std::string format_value(ParamHandle handle, double value) const;
  std::string restart_note(const std::vector<ParamWrite>& batch) const;

  ConsoleContext context_;
  ParameterStore& params_;
  Controller& controller_;
  bool walk_requested_ = false;
};

/// Splits a line into words at spaces.
std::vector<std::string> split_words(std::string_view line);

}  // namespace stride::fw::console
