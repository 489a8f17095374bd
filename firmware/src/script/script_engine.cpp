// ScriptEngine: deadline-timed keyframe playback (see the header for the timing model).
#include "stride/firmware/script/script_engine.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "stride/firmware/script/script_genome.hpp"
#include "stride/firmware/stand_pose.hpp"

namespace stride::fw {

namespace {

/// The parameters of a frame's wait and guard: (suffix, unit, bounds, the file's value).
struct CheckParam {
  const char* suffix;
  const char* unit;
  double min, max;
  double value;
};

std::array<CheckParam, 6> check_params(const ScriptFrame& frame) {
  constexpr double kHalfPi = 1.5707963267948966;
  return {{{"wait.pitch_min", "rad", -kHalfPi, kHalfPi, frame.wait.pitch_min_rad},
           {"wait.pitch_max", "rad", -kHalfPi, kHalfPi, frame.wait.pitch_max_rad},
           {"wait.rate_max", "rad/s", 0.0, 20.0, frame.wait.rate_max_rad_s},
           {"wait.timeout_ms", "ms", 0.0, kMaxFrameDurationMs,
            static_cast<double>(frame.wait.timeout_ms)},
           {"guard.pitch_min", "rad", -kHalfPi, kHalfPi, frame.guard.pitch_min_rad},
           {"guard.pitch_max", "rad", -kHalfPi, kHalfPi, frame.guard.pitch_max_rad}}};
}

}  // namespace

ScriptEngine::ScriptEngine(std::int64_t period_ns, ParameterStore& params, const ServoTable& servos,
                           const AttitudeEstimator* attitude)
    : period_ns_(period_ns), params_(params), servos_(servos), attitude_(attitude) {
  if (period_ns <= 0) throw std::invalid_argument("ScriptEngine: period_ns must be positive");
  duration_modifier_ = params_.add_real("script.duration_modifier", 1.0, 0.25, 4.0, "1",
                                        "multiplies every script frame duration (1 = as written)");
}

Status ScriptEngine::add_script(Script script) {
  const std::string origin = "script '" + script.name + "'";
  if (script.frames.empty() || script.frames.size() > kMaxScriptFrames) {
    return Status::error(origin + ": frames: must have 1.." + std::to_string(kMaxScriptFrames));
  }
  if (find(script.name) >= 0) return Status::error(origin + ": name: already loaded");
  // Check every parameter name and default before registering any (all or nothing).
  std::vector<ParamSpec> specs, duration_specs, check_specs;
  for (std::size_t f = 0; f < script.frames.size(); ++f) {
    for (const ScriptTarget& t : script.frames[f].targets) {
      if (t.servo >= hal::kServoCount) {
        return Status::error(origin + ": frames[" + std::to_string(f) + "]: bad servo index");
      }
      const ServoSpec& servo = servos_[t.servo];
      ParamSpec spec;
      spec.name = script_position_parameter(script.name, f, servo.name);
      spec.type = ParamType::kReal;
      spec.default_value = t.position_rad;
      spec.min = servo.min_rad;
      spec.max = servo.max_rad;
      spec.unit = "rad";
      spec.description = script.name + " frame " + std::to_string(f + 1) + " " + servo.name +
                         " target (URDF angle)";
      if (params_.find(spec.name)) {
        return Status::error(origin + ": parameter " + spec.name + " already registered");
      }
      if (!(t.position_rad >= spec.min && t.position_rad <= spec.max)) {
        return Status::error(origin + ": frames[" + std::to_string(f) + "] " + servo.name +
                             ": position " + format_number(t.position_rad) +
                             " outside the servo limits");
      }
      specs.push_back(std::move(spec));
    }
    ParamSpec duration;
    duration.name = script_duration_parameter(script.name, f);
    duration.type = ParamType::kReal;
    duration.default_value = script.frames[f].duration_ms;
    duration.min = 1.0;
    duration.max = kMaxFrameDurationMs;
    duration.unit = "ms";
    duration.description = script.name + " frame " + std::to_string(f + 1) +
                           " duration (before script.duration_modifier)";
    if (params_.find(duration.name)) {
      return Status::error(origin + ": parameter " + duration.name + " already registered");
    }
    duration_specs.push_back(std::move(duration));
    const ScriptFrame& frame = script.frames[f];
    const auto checks = check_params(frame);
    for (std::size_t k = 0; k < checks.size(); ++k) {
      if (!(k < 4 ? frame.wait.enabled : frame.guard.enabled)) continue;
      ParamSpec check;
      check.name =
          "script." + script.name + ".frame" + std::to_string(f + 1) + "." + checks[k].suffix;
      check.type = ParamType::kReal;
      check.default_value = checks[k].value;
      check.min = checks[k].min;
      check.max = checks[k].max;
      check.unit = checks[k].unit;
      check.description = script.name + " frame " + std::to_string(f + 1) + " " + checks[k].suffix +
                          " (the trunk's pitch from the attitude estimate)";
      if (params_.find(check.name)) {
        return Status::error(origin + ": parameter " + check.name + " already registered");
      }
      check_specs.push_back(std::move(check));
    }
  }
  LoadedScript loaded;
  std::size_t next_spec = 0, next_check = 0;
  loaded.handles.resize(script.frames.size());
  loaded.checks.resize(script.frames.size());
  for (std::size_t f = 0; f < script.frames.size(); ++f) {
    const auto& targets = script.frames[f].targets;
    loaded.durations.push_back(params_.add(std::move(duration_specs[f])));
    for (std::size_t k = 0; k < 6; ++k)
      if (k < 4 ? script.frames[f].wait.enabled : script.frames[f].guard.enabled)
        loaded.checks[f][k] = params_.add(std::move(check_specs[next_check++]));
    for (std::size_t j = 0; j < targets.size(); ++j) {
      loaded.handles[f].push_back(params_.add(std::move(specs[next_spec++])));
      loaded.queues[targets[j].servo].emplace_back(static_cast<std::uint16_t>(f),
                                                   static_cast<std::uint16_t>(j));
    }
  }
  loaded.script = std::move(script);
  scripts_.push_back(std::move(loaded));
  return {};
}

Status ScriptEngine::load_folder(const std::filesystem::path& folder) {
  std::vector<Script> scripts;
  if (Status s = load_script_folder(folder, servos_, scripts); !s) return s;
  for (const Script& script : scripts) {
    if (find(script.name) >= 0) {
      return Status::error(folder.string() + ": script '" + script.name + "' already loaded");
    }
  }
  for (Script& script : scripts) {
    if (Status s = add_script(std::move(script)); !s) return s;
  }
  return {};
}

ParamHandle ScriptEngine::position_handle(std::size_t index, std::size_t frame,
                                          std::size_t target) const {
  return scripts_.at(index).handles.at(frame).at(target);
}

int ScriptEngine::find(std::string_view script_name) const noexcept {
  for (std::size_t i = 0; i < scripts_.size(); ++i) {
    if (scripts_[i].script.name == script_name) return static_cast<int>(i);
  }
  return -1;
}

bool ScriptEngine::select(int script_index) noexcept {
  if (script_index < 0 || static_cast<std::size_t>(script_index) >= scripts_.size()) {
    return false;
  }
  selected_ = script_index;
  return true;
}

void ScriptEngine::start(const hal::SensorFrame& /*sensors*/,
                         const hal::CommandFrame& /*last_sent*/, hal::Tick tick) noexcept {
  playing_ = selected_;
  stepped_ = false;
  last_step_tick_ = tick;
  frame_ = 0;
  waiting_ = false;
  aborted_ = false;
  if (playing_ < 0) return;
  const LoadedScript& loaded = scripts_[static_cast<std::size_t>(playing_)];
  const double modifier = params_.value(duration_modifier_) * std::max(time_scale_, 0.0);
  const double period_ms = static_cast<double>(period_ns_) * 1e-6;
  double elapsed_ms = 0.0;  // integer-valued as written: the sum is exact
  hal::Tick previous = tick;
  for (std::size_t f = 0; f < loaded.script.frames.size(); ++f) {
    const ScriptFrame& frame = loaded.script.frames[f];
    elapsed_ms += params_.value(loaded.durations[f]);
    const auto offset = static_cast<hal::Tick>(std::llround(elapsed_ms * modifier / period_ms));
    deadlines_[f] = std::max(tick + offset, previous + 1);
    previous = deadlines_[f];
    for (std::size_t j = 0; j < frame.targets.size(); ++j) {
      positions_[f][frame.targets[j].servo] = params_.value(loaded.handles[f][j]);
    }
    FrameCheck& c = checks_[f];
    c = FrameCheck{};
    c.wait = frame.wait.enabled && attitude_ != nullptr;
    c.guard = frame.guard.enabled && attitude_ != nullptr;
    const auto& h = loaded.checks[f];
    if (c.wait) {
      c.wait_min = params_.value(h[0]);
      c.wait_max = params_.value(h[1]);
      c.rate_max = params_.value(h[2]);
      c.timeout_ticks = static_cast<hal::Tick>(std::llround(params_.value(h[3]) / period_ms));
    }
    if (c.guard) {
      c.guard_min = params_.value(h[4]);
      c.guard_max = params_.value(h[5]);
    }
  }
  for (ServoPlayback& p : playback_) p = ServoPlayback{};
}

void ScriptEngine::advance_frames(hal::Tick tick) noexcept {
  const std::size_t frames = scripts_[static_cast<std::size_t>(playing_)].script.frames.size();
  if (attitude_ == nullptr) return;  // played as timed
  const double pitch = attitude_->pitch();
  while (frame_ < frames) {
    const FrameCheck& c = checks_[frame_];
    if (c.guard && (pitch < c.guard_min || pitch > c.guard_max)) {
      aborted_ = true;
      return;
    }
    if (deadlines_[frame_] > tick) return;  // the frame plays on
    if (c.wait) {
      if (!waiting_) {
        waiting_ = true;
        wait_start_ = tick;
      }
      const bool met = pitch >= c.wait_min && pitch <= c.wait_max &&
                       std::abs(attitude_->gyro().y()) <= c.rate_max;
      if (!met) {
        if (tick - wait_start_ >= c.timeout_ticks) {
          aborted_ = true;
          return;
        }
        // Hold: this frame and every later one move back to keep this frame's deadline ahead.
        const hal::Tick delay = tick + 1 - deadlines_[frame_];
        for (std::size_t f = frame_; f < frames; ++f) deadlines_[f] += delay;
        return;
      }
      waiting_ = false;
    }
    ++frame_;
  }
}

void ScriptEngine::step(const hal::SensorFrame& sensors, hal::Tick tick,
                        hal::CommandFrame& out) noexcept {
  if (playing_ < 0 || aborted_) return;
  stepped_ = true;
  last_step_tick_ = tick;
  advance_frames(tick);
  if (aborted_) return;  // the servos keep the last commands; the motion manager takes over
  const LoadedScript& loaded = scripts_[static_cast<std::size_t>(playing_)];
  const double period_s = static_cast<double>(period_ns_) * 1e-9;
  for (std::size_t servo = 0; servo < hal::kServoCount; ++servo) {
    const auto& queue = loaded.queues[servo];
    if (queue.empty()) continue;
    ServoPlayback& p = playback_[servo];
    while (p.cursor < queue.size() && deadlines_[queue[p.cursor].first] <= tick) ++p.cursor;
    hal::ServoCommand& cmd = out.servos[servo];
    const bool finished = p.cursor >= queue.size();
    const auto [frame, target_index] = finished ? queue.back() : queue[p.cursor];
    const ScriptTarget& target = loaded.script.frames[frame].targets[target_index];
    const double goal = positions_[frame][servo];
    if (finished) {
      p.speed_rad_s = 0.0;  // deadline passed: full speed, as on the robot
    } else if (p.activated != p.cursor) {
      const hal::ServoState& state = sensors.servos[servo];
      const bool answered =
          state.health == hal::DeviceHealth::kOk || state.health == hal::DeviceHealth::kError;
      const double present = answered ? state.position_rad : cmd.position_rad;
      const double time_left = static_cast<double>(deadlines_[frame] - tick) * period_s;
      p.speed_rad_s = std::max(std::abs(goal - present) / time_left, kMinMovingSpeed);
      p.activated = p.cursor;
    }
    cmd.position_rad = goal;
    cmd.moving_speed_rad_s = p.speed_rad_s;
    cmd.p_gain = gain_to_p_register(target.gain);
    cmd.i_gain = 0.0;
    cmd.d_gain = 0.0;
    cmd.torque_limit = torque_limit_from_percent(target.torque);
    cmd.torque_enable = target.torque > 0.0;
  }
}

hal::Tick ScriptEngine::end_tick() const noexcept {
  if (playing_ < 0) return last_step_tick_;
  const auto frames = scripts_[static_cast<std::size_t>(playing_)].script.frames.size();
  return deadlines_[frames - 1];
}

bool ScriptEngine::done() const noexcept {
  if (playing_ < 0 || aborted_) return true;
  return stepped_ && last_step_tick_ >= end_tick();
}

}  // namespace stride::fw
