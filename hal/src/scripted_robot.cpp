// ScriptedRobot implementation (see the header).
#include "stride/hal/scripted_robot.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace stride::hal {

ScriptedRobot::ScriptedRobot(Options options, std::vector<SensorFrame> frames)
    : options_(options), frames_(std::move(frames)) {
  if (frames_.empty()) throw std::invalid_argument("ScriptedRobot: needs at least one frame");
  if (options_.period_ns <= 0) throw std::invalid_argument("ScriptedRobot: period_ns must be > 0");
  recorded_.reserve(options_.record_capacity);
  for (std::size_t i = 0; i < kServoCount; ++i) {
    echo_position_[i] = frames_.front().servos[i].position_rad;
  }
  for (auto& d : diagnostics_.devices) d.health = DeviceHealth::kOk;
}

void ScriptedRobot::inject_late_wakeup(Tick tick, Tick woken) {
  late_wakeups_.emplace_back(tick, std::max(tick, woken));
}

Tick ScriptedRobot::sleep_until(Tick tick) noexcept {
  Tick woken = tick;
  for (const auto& [at, late] : late_wakeups_) {
    if (at == tick) woken = late;
  }
  current_tick_ = woken;
  return woken;
}

void ScriptedRobot::read(SensorFrame& out) noexcept {
  const std::size_t index = std::min(reads_, frames_.size() - 1);
  out = frames_[index];
  out.tick = current_tick_;
  ++reads_;
  if (options_.echo_commands && have_command_) {
    const double dt = static_cast<double>(options_.period_ns) * 1e-9;
    for (std::size_t i = 0; i < kServoCount; ++i) {
      const ServoCommand& c = last_command_.servos[i];
      double& q = echo_position_[i];
      if (c.torque_enable && std::isfinite(c.position_rad)) {
        const double step = c.position_rad - q;
        const double max_step = c.moving_speed_rad_s > 0.0 ? c.moving_speed_rad_s * dt : 1e9;
        q += std::clamp(step, -max_step, max_step);
      }
      out.servos[i].position_rad = q;
      out.servos[i].goal_position_rad = c.position_rad;
      out.servos[i].p_gain = c.p_gain;
      out.servos[i].torque_limit = c.torque_limit;
      out.servos[i].torque_enabled = c.torque_enable;
    }
  }
}

void ScriptedRobot::write(const CommandFrame& commands) noexcept {
  ++writes_;
  ++diagnostics_.cycles;
  last_command_ = commands;
  have_command_ = true;
  if (recorded_.size() < options_.record_capacity) recorded_.push_back(commands);
}

void ScriptedRobot::set_torque_enable(bool enabled) noexcept {
  torque_enabled_ = enabled;
}

SensorFrame ScriptedRobot::standing_frame(const std::array<double, kServoCount>& position_rad) {
  SensorFrame frame;
  frame.cm730.accel_mps2 = {0.0, 0.0, 9.80665};
  frame.cm730.voltage_v = 15.0;
  frame.cm730.health = DeviceHealth::kOk;
  for (std::size_t i = 0; i < kServoCount; ++i) {
    ServoState& s = frame.servos[i];
    s.position_rad = position_rad[i];
    s.goal_position_rad = position_rad[i];
    s.voltage_v = 15.0;
    s.temperature_c = 35.0;
    s.p_gain = 32.0;
    s.torque_limit = 1.0;
    s.health = DeviceHealth::kOk;
  }
  return frame;
}

}  // namespace stride::hal
