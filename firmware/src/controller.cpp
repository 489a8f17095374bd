// Controller implementation.
#include "stride/firmware/controller.hpp"

#include <cstring>

namespace stride::fw {

Controller::Controller(ParameterStore& params, const ServoTable& servos, std::int64_t period_ns,
                       AttitudeEstimator& attitude, Engines engines)
    : period_ns_(period_ns),
      attitude_(attitude),
      safety_(params, servos),
      motion_(params, static_cast<double>(period_ns) * 1e-9, engines.walk, engines.script) {}

void Controller::request(const MotionRequest& request) {
  std::lock_guard lock(inbox_mutex_);
  if (inbox_size_ == inbox_.size()) {
    ++dropped_;
    return;
  }
  inbox_[inbox_size_++] = request;
}

void Controller::set_torque(bool on) {
  std::lock_guard lock(inbox_mutex_);
  torque_change_pending_ = true;
  torque_change_on_ = on;
}

void Controller::take_inbox() noexcept {
  std::unique_lock lock(inbox_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // a writer is busy: take the requests next tick
  // The manager keeps one pending request per tick: hand over the oldest now and keep the
  // rest for the following ticks, so a script request is not overwritten by a later one.
  if (inbox_size_ > 0) {
    motion_.request(inbox_[0]);
    for (std::size_t i = 1; i < inbox_size_; ++i) inbox_[i - 1] = inbox_[i];
    --inbox_size_;
  }
  if (torque_change_pending_) {
    torque_change_pending_ = false;
    torque_on_ = torque_change_on_;
    if (torque_on_) safety_.reset_latches();
  }
}

hal::CommandFrame Controller::step(const hal::SensorFrame& sensors, hal::Tick tick) noexcept {
  take_inbox();
  attitude_.update(sensors.cm730);
  safety_.observe(sensors, attitude_);
  commands_.tick = tick;
  motion_.step(sensors, tick,
               FallSignal{safety_.fallen(), safety_.falling(), safety_.report().fall_direction,
                          safety_.report().fall_tilt_rad},
               commands_);
  if (!torque_on_) {
    for (auto& c : commands_.servos) c.torque_enable = false;
  }
  safety_.apply(sensors, commands_);

  std::unique_lock lock(status_mutex_, std::try_to_lock);
  if (lock.owns_lock()) {
    published_.tick = tick;
    published_.state = motion_.state();
    published_.script.fill(0);
    const std::string_view script = motion_.active_script();
    std::memcpy(
        published_.script.data(), script.data(),
        script.size() < published_.script.size() ? script.size() : published_.script.size() - 1);
    published_.torque_on = torque_on_;
    published_.refused_requests = motion_.refused_requests();
    published_.dropped_requests = dropped_;
    published_.safety = safety_.report();
    published_.sensors = sensors;
  }
  return commands_;
}

ControllerStatus Controller::status() const {
  std::lock_guard lock(status_mutex_);
  return published_;
}

}  // namespace stride::fw
