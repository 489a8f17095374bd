// CommandInterpreter implementation: parsing, validation and the replies of every command.
#include "stride/firmware/console/command_interpreter.hpp"

#include <charconv>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <thread>

#include <nlohmann/json.hpp>

namespace stride::fw::console {

std::vector<std::string> split_words(std::string_view line) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && line[i] == ' ') ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ') ++i;
    if (i > start) words.emplace_back(line.substr(start, i - start));
  }
  return words;
}

namespace {

bool parse_double(std::string_view text, double& out) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size() && !text.empty();
}

bool parse_value(const ParamSpec& spec, std::string_view text, double& out) {
  if (spec.type == ParamType::kBool) {
    if (text == "true" || text == "on" || text == "1") {
      out = 1.0;
      return true;
    }
    if (text == "false" || text == "off" || text == "0") {
      out = 0.0;
      return true;
    }
    return false;
  }
  return parse_double(text, out);
}

std::string shortest(double value) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (ec != std::errc()) return format_number(value);
  return std::string(buffer, end);
}

std::string_view health_name(hal::DeviceHealth health) {
  switch (health) {
    case hal::DeviceHealth::kOk:
      return "ok";
    case hal::DeviceHealth::kError:
      return "error";
    case hal::DeviceHealth::kTimeout:
      return "timeout";
    case hal::DeviceHealth::kMissing:
      return "missing";
  }
  return "?";
}

std::string printf_line(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string printf_line(const char* format, ...) {
  char buffer[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buffer, sizeof buffer, format, args);
  va_end(args);
  return buffer;
}

struct CommandHelp {
  const char* usage;
  const char* summary;
};
constexpr CommandHelp kCommands[] = {
    {"help", "this list"},
    {"list [PREFIX]", "parameters: value, unit, type, bounds, default, flags"},
    {"get NAME", "one parameter's live value"},
    {"set NAME VALUE", "change a parameter (applied at the next tick)"},
    {"reset NAME|all", "back to the default value(s)"},
    {"save [FILE]", "write the live values to a JSON file (atomically)"},
    {"load [FILE]", "apply a parameter file (validated as a whole first)"},
    {"flash JSON", "apply a whole parameter file sent as one line of JSON"},
    {"status", "motion state, loop statistics, bus health, servos"},
    {"torque on|off [force]", "servo torque ('force' allows off while moving)"},
    {"walk VX VY VTHETA", "walk; velocities normalised to [-1, 1]"},
    {"stop", "stop walking or playing and stand"},
    {"script NAME", "play a keyframe script"},
};

}  // namespace

CommandInterpreter::CommandInterpreter(ConsoleContext context)
    : context_(std::move(context)), params_(*context_.params), controller_(*context_.controller) {}

MotionSituation CommandInterpreter::situation() const {
  const ControllerStatus s = controller_.status();
  return {s.state, walk_requested_, s.torque_on};
}

Reply CommandInterpreter::execute(std::string_view line) {
  // A fall cancels the walk inside the motion manager; forget the console's request too.
  const MotionState state = controller_.status().state;
  if (state == MotionState::kFallen || state == MotionState::kGetUp ||
      state == MotionState::kFalling)
    walk_requested_ = false;

  const Args args = split_words(line);
  if (args.empty()) return Reply::success();
  const std::string& command = args[0];
  if (command == "help") return help();
  if (command == "list") return list(args);
  if (command == "get") return get(args);
  if (command == "set") return set(args);
  if (command == "reset") return reset(args);
  if (command == "save") return save(args);
  if (command == "load") return load(args);
  if (command == "flash") {
    const std::size_t at = line.find("flash");
    return flash(line.substr(at + 5));
  }
  if (command == "status") return status();
  if (command == "torque") return torque(args);
  if (command == "walk") return walk(args);
  if (command == "stop") return stop();
  if (command == "script") return script(args);
  std::string shown = command.size() > 40 ? command.substr(0, 40) + "..." : command;
  return Reply::error(ErrorCode::kUnknownCommand, "'" + shown + "' (type help)");
}

Reply CommandInterpreter::help() const {
  Reply r;
  for (const auto& c : kCommands) r.data.push_back(printf_line("%-22s %s", c.usage, c.summary));
  r.final_line = "ok " + std::to_string(std::size(kCommands)) + " commands";
  return r;
}

std::string CommandInterpreter::format_value(ParamHandle handle, double value) const {
  const ParamSpec& spec = params_.spec(handle);
  if (spec.type == ParamType::kBool) return value != 0.0 ? "true" : "false";
  if (spec.type == ParamType::kInt) return std::to_string(static_cast<long long>(value));
  return shortest(value);
}

Reply CommandInterpreter::list(const Args& args) const {
  if (args.size() > 2) return Reply::error(ErrorCode::kUsage, "list [PREFIX]");
  const std::string prefix = args.size() == 2 ? args[1] : "";
  Reply r;
  for (ParamHandle h : params_.list(prefix)) {
    const ParamSpec& s = params_.spec(h);
    std::string text = s.name + " = " + format_value(h, params_.value(h));
    if (!s.unit.empty() && s.unit != "1") text += " " + s.unit;
    text += "  " + std::string(to_string(s.type));
    if (s.type != ParamType::kBool)
      text += " [" + format_number(s.min) + ", " + format_number(s.max) + "]";
    text += " default " + format_value(h, s.default_value);
    if (s.read_only) text += " read-only";
    if (s.needs_restart) text += " needs-restart";
    text += "  # " + s.description;
    r.data.push_back(std::move(text));
  }
  r.final_line = "ok " + std::to_string(r.data.size()) + " parameters";
  return r;
}

Reply CommandInterpreter::get(const Args& args) const {
  if (args.size() != 2) return Reply::error(ErrorCode::kUsage, "get NAME");
  const auto handle = params_.find(args[1]);
  if (!handle) return Reply::error(ErrorCode::kUnknownParameter, "'" + args[1] + "' (try list)");
  return Reply::success(args[1] + " = " + format_value(*handle, params_.value(*handle)));
}

std::string CommandInterpreter::restart_note(const std::vector<ParamWrite>& batch) const {
  std::string names;
  for (const auto& [name, value] : batch) {
    const auto h = params_.find(name);
    if (h && params_.spec(*h).needs_restart && params_.value(*h) != value) {
      names += (names.empty() ? "" : ", ") + name;
    }
  }
  if (names.empty()) return {};
  return " (" + names + " takes effect after a restart: save, then restart stride-fw)";
}

Reply CommandInterpreter::stage_batch(const std::vector<ParamWrite>& batch, std::string done_text) {
  if (Status s = check_writes(params_, batch, situation()); !s) {
    return Reply::error(ErrorCode::kRefused, s.message());
  }
  const std::string note = restart_note(batch);
  if (Status s = params_.stage(batch); !s) return Reply::error(ErrorCode::kBadValue, s.message());
  const auto deadline = std::chrono::steady_clock::now() + context_.apply_timeout;
  bool applied = !params_.has_staged();
  while (!applied && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    applied = !params_.has_staged();
  }
  if (!applied) done_text += " (staged; the loop has not applied it yet)";
  return Reply::success(done_text + note);
}

Reply CommandInterpreter::set(const Args& args) {
  if (args.size() != 3) return Reply::error(ErrorCode::kUsage, "set NAME VALUE");
  const auto handle = params_.find(args[1]);
  if (!handle) return Reply::error(ErrorCode::kUnknownParameter, "'" + args[1] + "' (try list)");
  const ParamSpec& spec = params_.spec(*handle);
  if (spec.read_only) return Reply::error(ErrorCode::kReadOnly, spec.name + " is read-only");
  double value = 0.0;
  if (!parse_value(spec, args[2], value)) {
    return Reply::error(ErrorCode::kBadValue,
                        spec.name + ": '" + args[2] + "' is not a " +
                            (spec.type == ParamType::kBool ? std::string("bool (true|false)")
                                                           : std::string(to_string(spec.type))));
  }
  if (Status s = params_.check(spec.name, value); !s) {
    return Reply::error(ErrorCode::kBadValue, s.message());
  }
  return stage_batch({{spec.name, value}}, spec.name + " = " + format_value(*handle, value));
}

Reply CommandInterpreter::reset(const Args& args) {
  if (args.size() != 2) return Reply::error(ErrorCode::kUsage, "reset NAME|all");
  std::vector<ParamWrite> batch;
  if (args[1] == "all") {
    for (ParamHandle h : params_.list()) {
      const ParamSpec& s = params_.spec(h);
      if (!s.read_only) batch.emplace_back(s.name, s.default_value);
    }
    return stage_batch(batch, "reset " + std::to_string(batch.size()) + " parameters");
  }
  const auto handle = params_.find(args[1]);
  if (!handle) return Reply::error(ErrorCode::kUnknownParameter, "'" + args[1] + "' (try list)");
  const ParamSpec& spec = params_.spec(*handle);
  if (spec.read_only) return Reply::error(ErrorCode::kReadOnly, spec.name + " is read-only");
  batch.emplace_back(spec.name, spec.default_value);
  return stage_batch(batch, spec.name + " = " + format_value(*handle, spec.default_value));
}

Reply CommandInterpreter::save(const Args& args) const {
  if (args.size() > 2) return Reply::error(ErrorCode::kUsage, "save [FILE]");
  const std::filesystem::path file =
      args.size() == 2 ? std::filesystem::path(args[1]) : context_.default_file;
  if (Status s = params_.save_file(file); !s) return Reply::error(ErrorCode::kIo, s.message());
  return Reply::success("saved " + std::to_string(params_.size()) + " parameters to " +
                        file.string());
}

Reply CommandInterpreter::load(const Args& args) {
  if (args.size() > 2) return Reply::error(ErrorCode::kUsage, "load [FILE]");
  const std::filesystem::path file =
      args.size() == 2 ? std::filesystem::path(args[1]) : context_.default_file;
  if (!std::ifstream(file)) {
    return Reply::error(ErrorCode::kIo, file.string() + ": cannot open for reading");
  }
  std::vector<ParamWrite> batch;
  if (Status s = params_.parse_json_file(file, batch); !s) {
    return Reply::error(ErrorCode::kBadFile, s.message() + " (nothing applied)");
  }
  return stage_batch(
      batch, "loaded " + std::to_string(batch.size()) + " parameters from " + file.string());
}

Reply CommandInterpreter::flash(std::string_view json) {
  while (!json.empty() && json.front() == ' ') json.remove_prefix(1);
  if (json.empty())
    return Reply::error(ErrorCode::kUsage, "flash {JSON parameter file on one line}");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json);
  } catch (const nlohmann::json::exception& e) {
    return Reply::error(ErrorCode::kBadFile,
                        std::string("flash: not valid JSON (") + e.what() + "); nothing applied");
  }
  std::vector<ParamWrite> batch;
  if (Status s = params_.parse_json(doc, batch, "flash"); !s) {
    return Reply::error(ErrorCode::kBadFile, s.message() + " (nothing applied)");
  }
  return stage_batch(batch, "flashed " + std::to_string(batch.size()) + " parameters");
}

Reply CommandInterpreter::status() const {
  const ControllerStatus s = controller_.status();
  Reply r;
  std::string motion = "motion: " + std::string(to_string(s.state));
  if (s.script[0] != '\0') motion += " (" + std::string(s.script.data()) + ")";
  motion +=
      printf_line("  walk requested: %s  torque: %s  tick: %lld", walk_requested_ ? "yes" : "no",
                  s.torque_on ? "on" : "off", static_cast<long long>(s.tick));
  r.data.push_back(motion);
  r.data.push_back(
      printf_line("requests: refused %u  dropped %u", s.refused_requests, s.dropped_requests));
  r.data.push_back(printf_line("parameters: %zu  batches applied %llu  staged: %s", params_.size(),
                               static_cast<unsigned long long>(params_.applied_batches()),
                               params_.has_staged() ? "yes" : "no"));
  if (context_.loop_status) {
    for (auto& line : context_.loop_status()) r.data.push_back(std::move(line));
  }
  std::string latched;
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    if (s.safety.torque_off_latched[i])
      latched += (latched.empty() ? "" : ",") + std::to_string(i + 1);
  }
  r.data.push_back(
      printf_line("safety: fallen %s  tilt %.3f rad  falls %u  torque clamps %u  "
                  "torque off (errors): %s",
                  s.safety.fallen ? "yes" : "no", s.safety.tilt_rad, s.safety.falls,
                  s.safety.torque_clamps, latched.empty() ? "none" : latched.c_str()));
  const auto& imu = s.sensors.cm730;
  r.data.push_back(printf_line(
      "cm730: accel %.2f %.2f %.2f m/s2  gyro %.3f %.3f %.3f rad/s  battery %.1f V  health %s  "
      "errors 0x%02x",
      imu.accel_mps2[0], imu.accel_mps2[1], imu.accel_mps2[2], imu.gyro_rad_s[0], imu.gyro_rad_s[1],
      imu.gyro_rad_s[2], imu.voltage_v, std::string(health_name(imu.health)).c_str(),
      imu.error_flags));
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const auto& servo = s.sensors.servos[i];
    const std::string name = context_.servos != nullptr ? (*context_.servos)[i].name : "";
    r.data.push_back(printf_line(
        "servo %2zu %-17s pos %+.4f rad  temp %5.1f C  load %+.2f  health %-7s errors 0x%02x  "
        "clamps %u",
        i + 1, name.c_str(), servo.position_rad, servo.temperature_c, servo.load,
        std::string(health_name(servo.health)).c_str(), servo.error_flags,
        s.safety.limit_clamps[i]));
  }
  r.final_line = "ok status";
  return r;
}

bool CommandInterpreter::wait_for_torque(bool on) const {
  // The switch lands at the next tick; wait for the published status so that a following
  // command (walk after torque on) sees it.
  const auto deadline = std::chrono::steady_clock::now() + context_.apply_timeout;
  for (;;) {
    if (controller_.status().torque_on == on) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

Reply CommandInterpreter::torque(const Args& args) {
  const bool force = args.size() == 3 && args[2] == "force";
  if (args.size() < 2 || args.size() > 3 || (args.size() == 3 && !force) ||
      (args[1] != "on" && args[1] != "off") || (force && args[1] != "off")) {
    return Reply::error(ErrorCode::kUsage, "torque on|off [force]");
  }
  if (args[1] == "on") {
    controller_.set_torque(true);
    return Reply::success(wait_for_torque(true) ? "torque on"
                                                : "torque on (requested; the loop has not "
                                                  "applied it yet)");
  }
  const MotionSituation now = situation();
  if (Status s = check_torque_off(now, force); !s) {
    return Reply::error(ErrorCode::kRefused, s.message());
  }
  if (now.moving()) {  // forced: also cancel the motion so it does not resume limp
    controller_.request(MotionRequest::stand());
    walk_requested_ = false;
  }
  controller_.set_torque(false);
  return Reply::success(wait_for_torque(false) ? "torque off"
                                               : "torque off (requested; the loop has not "
                                                 "applied it yet)");
}

Reply CommandInterpreter::walk(const Args& args) {
  if (args.size() != 4)
    return Reply::error(ErrorCode::kUsage, "walk VX VY VTHETA (each in [-1, 1])");
  double v[3] = {0.0, 0.0, 0.0};
  static constexpr const char* kNames[3] = {"vx", "vy", "vtheta"};
  for (int i = 0; i < 3; ++i) {
    if (!parse_double(args[static_cast<std::size_t>(i) + 1], v[i]) || !std::isfinite(v[i])) {
      return Reply::error(ErrorCode::kBadValue, std::string(kNames[i]) + ": '" +
                                                    args[static_cast<std::size_t>(i) + 1] +
                                                    "' is not a number");
    }
    if (v[i] < -1.0 || v[i] > 1.0) {
      return Reply::error(ErrorCode::kBadValue, std::string(kNames[i]) + ": " + shortest(v[i]) +
                                                    " outside the allowed range [-1, 1]");
    }
  }
  if (Status s = check_walk(situation()); !s) return Reply::error(ErrorCode::kRefused, s.message());
  controller_.request(MotionRequest::walk(v[0], v[1], v[2]));
  walk_requested_ = true;
  return Reply::success("walk requested vx=" + shortest(v[0]) + " vy=" + shortest(v[1]) +
                        " vtheta=" + shortest(v[2]));
}

Reply CommandInterpreter::stop() {
  controller_.request(MotionRequest::stand());
  walk_requested_ = false;
  return Reply::success("stop requested");
}

Reply CommandInterpreter::script(const Args& args) {
  if (args.size() != 2) return Reply::error(ErrorCode::kUsage, "script NAME");
  const std::string& name = args[1];
  bool valid = name.size() < 32;
  for (char c : name) {
    valid = valid && ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-');
  }
  if (!valid) {
    return Reply::error(ErrorCode::kBadValue, "script name must be 1-31 characters of a-z 0-9 _ -");
  }
  const MotionSituation now = situation();
  if (!now.torque_on)
    return Reply::error(ErrorCode::kRefused, "script with the torque off; send 'torque on' first");
  if (now.state == MotionState::kFallen || now.state == MotionState::kGetUp ||
      now.state == MotionState::kFalling) {
    return Reply::error(ErrorCode::kRefused, "script while " + now.describe());
  }
  controller_.request(MotionRequest::play(name));
  walk_requested_ = false;  // a script request stops the walk first
  return Reply::success("script " + name + " requested");
}

}  // namespace stride::fw::console
