// MotionManager implementation (see the header for the state machine).
#include "stride/firmware/motion_manager.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "stride/firmware/stand_pose.hpp"

namespace stride::fw {

std::string_view to_string(MotionState state) {
  switch (state) {
    case MotionState::kStand:
      return "stand";
    case MotionState::kWalk:
      return "walk";
    case MotionState::kScript:
      return "script";
    case MotionState::kFallen:
      return "fallen";
    case MotionState::kGetUp:
      return "get_up";
    case MotionState::kFalling:
      return "falling";
  }
  return "?";
}

namespace {
// want_script_ while a script plays: a stand request (the console's `stop`) ends it at once.
constexpr int kStopScript = -2;

void copy_name(std::array<char, 32>& to, std::string_view name) {
  to.fill('\0');
  std::memcpy(to.data(), name.data(), std::min(name.size(), to.size() - 1));
}
}  // namespace

MotionManager::MotionManager(ParameterStore& params, double period_s, WalkControl* walk,
                             ScriptControl* script)
    : params_(params),
      period_s_(period_s),
      stand_(params, period_s),
      protection_(params),
      walk_(walk),
      script_(script) {
  fallen_settle_time_ =
      params.add_real("motion.fallen_settle_time", 1.0, 0.0, 10.0, "s",
                      "longest wait after a fall before a get-up starts, still or not");
  // Lying still: a robot at rest reads its gyro's bias and noise, a few hundredths of a rad/s
  // (CM730: 0.01 rad/s bias, 0.005 noise in sim_hal/src/igus_defaults.cpp; the register's
  // step is 0.05 rad/s), while one still settling or rocking after the impact turns faster
  // than 0.5 rad/s. 0.2 s is two periods of the settling bounce measured on the turf.
  fallen_still_time_ = params.add_real("motion.fallen_still_time", 0.2, 0.0, 10.0, "s",
                                       "the get-up starts once the robot lies still this long");
  fallen_still_rate_ = params.add_real("motion.fallen_still_rate", 0.5, 0.0, 10.0, "rad/s",
                                       "lying still: every gyro axis below this rate");
  fallen_gain_ = params.add_real("motion.fallen_gain", 5.0, 0.0, 100.0, "1",
                                 "servo gain while fallen (0-100), soft to protect the robot");
  get_up_enabled_ = params.add({"motion.get_up", ParamType::kBool, 1, 0, 1, "",
                                "get up automatically after a fall", false, false});
  get_up_roll_ = params.add({"motion.get_up_roll", ParamType::kBool, 1, 0, 1, "",
                             "after a failed get-up from the back, roll onto the front "
                             "(script roll_to_front) and get up from there",
                             false, false});
  get_up_retry_ = params.add({"motion.get_up_retry", ParamType::kBool, 1, 0, 1, "",
                              "after a failed get-up, get up from the front with "
                              "get_up_front_retry (a quicker push-up at a higher servo load)",
                              false, false});
  get_up_slow_after_ = params.add(
      {"motion.get_up_slow_after", ParamType::kInt, 2, 0, 10, "attempts",
       "from this many failed get-ups on, play the get-ups slower (0: never)", false, false});
  get_up_slow_scale_ =
      params.add_real("motion.get_up_slow_scale", 1.5, 1.0, 3.0, "1",
                      "frame durations of the slower get-up, times the script's own");
  if (script_ != nullptr) {
    get_up_front_ = script_->find("get_up_front");
    get_up_back_ = script_->find("get_up_back");
    roll_to_front_ = script_->find("roll_to_front");
    get_up_front_retry_ = script_->find("get_up_front_retry");
  }
}

void MotionManager::request(const MotionRequest& request) noexcept {
  pending_ = request;
  have_request_ = true;
}

void MotionManager::enter(MotionState state, MotionEngine& engine, const hal::SensorFrame& sensors,
                          const hal::CommandFrame& last, hal::Tick tick) noexcept {
  state_ = state;
  engine.start(sensors, last, tick);
  if (state != MotionState::kScript && state != MotionState::kGetUp) active_script_name_.fill(0);
}

bool MotionManager::start_script(int index, std::string_view name, const hal::SensorFrame& sensors,
                                 const hal::CommandFrame& last, hal::Tick tick) noexcept {
  if (script_ == nullptr || !script_->select(index)) return false;
  copy_name(active_script_name_, name);
  const bool get_up = index == get_up_front_ || index == get_up_back_ || index == roll_to_front_ ||
                      index == get_up_front_retry_;
  const MotionState next =
      get_up && state_ == MotionState::kFallen ? MotionState::kGetUp : MotionState::kScript;
  state_ = next;
  playing_get_up_ = next == MotionState::kGetUp ? index : -1;
  // The slower variant after failed attempts (a get-up only; a roll and other scripts as timed).
  const auto slow_after = static_cast<int>(params_.value(get_up_slow_after_));
  const bool slow = next == MotionState::kGetUp && index != roll_to_front_ &&
                    index != get_up_front_retry_ && slow_after > 0 && failed_get_ups_ >= slow_after;
  script_->set_time_scale(slow ? params_.value(get_up_slow_scale_) : 1.0);
  script_->start(sensors, last, tick);
  return true;
}

void MotionManager::hold_soft(const hal::SensorFrame& sensors, hal::CommandFrame& out) noexcept {
  const double p_gain = gain_to_p_register(params_.value(fallen_gain_));
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    hal::ServoCommand& c = out.servos[i];
    const double measured = sensors.servos[i].position_rad;
    if (std::isfinite(measured)) c.position_rad = measured;
    c.moving_speed_rad_s = 0.0;
    c.p_gain = p_gain;
    c.torque_enable = true;
  }
}

/// 1. The latest request (stand, walk, script) turned into what the manager wants next.
void MotionManager::take_request() noexcept {
  if (!have_request_) return;
  have_request_ = false;
  switch (pending_.kind) {
    case MotionRequest::Kind::kStand:
      want_walk_ = false;
      want_script_ = -1;
      if (state_ == MotionState::kWalk) walk_->request_stop();
      if (state_ == MotionState::kScript) want_script_ = kStopScript;  // stand from here
      break;
    case MotionRequest::Kind::kWalk:
      if (walk_ == nullptr) {
        ++refused_;
        break;
      }
      walk_vx_ = std::clamp(pending_.vx, -1.0, 1.0);
      walk_vy_ = std::clamp(pending_.vy, -1.0, 1.0);
      walk_vtheta_ = std::clamp(pending_.vtheta, -1.0, 1.0);
      want_walk_ = true;
      want_script_ = -1;
      if (state_ == MotionState::kWalk) walk_->set_velocity(walk_vx_, walk_vy_, walk_vtheta_);
      break;
    case MotionRequest::Kind::kScript: {
      const int index = script_ != nullptr ? script_->find(pending_.script_name()) : -1;
      if (index < 0 || state_ == MotionState::kFallen || state_ == MotionState::kGetUp) {
        ++refused_;
        break;
      }
      want_script_ = index;
      copy_name(want_script_name_, pending_.script_name());
      want_walk_ = false;
      if (state_ == MotionState::kWalk) walk_->request_stop();
      break;
    }
  }
}

/// 2. Falls pre-empt everything but a get-up in progress.
void MotionManager::note_fall(const FallSignal& fall, hal::Tick tick) noexcept {
  const bool fallen = fall.fallen;
  if (fallen && state_ != MotionState::kFallen && state_ != MotionState::kGetUp) {
    relaxed_ = state_ == MotionState::kFalling;  // a protected fall relaxes through the impact
    state_ = MotionState::kFallen;
    failed_get_ups_ = 0;
    back_attempt_failed_ = false;
    fallen_since_ = tick;
    moving_since_fall_ = tick;
    want_walk_ = false;
    want_script_ = -1;
    active_script_name_.fill(0);
  }

  // 2b. A predicted fall: the protective pose, soft, until the fall is detected (kFallen) or
  // the prediction has cleared for fall.hold_time_s.
  if (fall.falling && protection_.enabled() &&
      (state_ == MotionState::kStand || state_ == MotionState::kWalk ||
       state_ == MotionState::kScript)) {
    state_ = MotionState::kFalling;
    falling_direction_ = fall.direction;
    relaxed_ = false;
    want_walk_ = false;
    want_script_ = -1;
    active_script_name_.fill(0);
  }
  if (state_ == MotionState::kFalling && fall.falling) falling_clear_since_ = tick;
  if (state_ == MotionState::kFalling && fall.tilt_rad > protection_.relax_tilt_rad())
    relaxed_ = true;
}

/// Lying: wait until the robot lies still (or long enough), then play the get-up script of the
/// side it lies on; relaxed through a protected fall's impact, else held soft.
void MotionManager::step_fallen(const hal::SensorFrame& sensors, hal::Tick tick, bool fallen,
                                const hal::CommandFrame& last, hal::CommandFrame& out) noexcept {
  const double lying = static_cast<double>(tick - fallen_since_) * period_s_;
  const auto& gyro = sensors.cm730.gyro_rad_s;
  const double rate_limit = params_.value(fallen_still_rate_);
  if (std::abs(gyro[0]) >= rate_limit || std::abs(gyro[1]) >= rate_limit ||
      std::abs(gyro[2]) >= rate_limit)
    moving_since_fall_ = tick;
  const double still = static_cast<double>(tick - moving_since_fall_) * period_s_;
  if (!fallen) {  // righted by someone: stand up from here
    enter(MotionState::kStand, stand_, sensors, last, tick);
    stand_.step(sensors, tick, out);
    return;
  }
  const bool settled =
      still >= params_.value(fallen_still_time_) || lying >= params_.value(fallen_settle_time_);
  if (params_.value(get_up_enabled_) != 0.0 && settled) {
    const auto& a = sensors.cm730.accel_mps2;
    const bool on_front = a[0] < 0.0;  // torso x axis points down
    // On a side, wait until it lies still (it may still roll over), at most one more settle
    // time, then play the script of the side the torso leans to: its first frames tip the
    // robot onto its front or back, and the retry picks the script for that side. (Without
    // this a robot lying still on a side stayed down for ever.)
    const bool clear = std::abs(a[0]) > std::abs(a[1]) ||
                       still >= params_.value(fallen_still_time_) ||
                       lying >= 2.0 * params_.value(fallen_settle_time_);
    int index = on_front ? get_up_front_ : get_up_back_;
    std::string_view name = on_front ? "get_up_front" : "get_up_back";
    // After a failed attempt from the back: roll onto the front first.
    if (!on_front && back_attempt_failed_ && roll_to_front_ >= 0 &&
        params_.value(get_up_roll_) != 0.0) {
      index = roll_to_front_;
      name = "roll_to_front";
    }
    // On the front after an odd number of failed attempts: the quicker push-up (after an even
    // number, the gentle one again, slower from motion.get_up_slow_after on): each attempt
    // differs from the one before.
    if (on_front && failed_get_ups_ % 2 == 1 && get_up_front_retry_ >= 0 &&
        params_.value(get_up_retry_) != 0.0) {
      index = get_up_front_retry_;
      name = "get_up_front_retry";
    }
    if (clear && index >= 0 && start_script(index, name, sensors, last, tick)) {
      relaxed_ = false;
      script_->step(sensors, tick, out);
      return;
    }
  }
  if (relaxed_ && lying < protection_.relax_time_s()) {  // through the impact: torque off
    for (auto& c : out.servos) c.torque_enable = false;
    return;
  }
  relaxed_ = false;
  hold_soft(sensors, out);
}

void MotionManager::step(const hal::SensorFrame& sensors, hal::Tick tick, const FallSignal& fall,
                         hal::CommandFrame& out) noexcept {
  const bool fallen = fall.fallen;
  const hal::CommandFrame& last = out;  // holds the previous tick's commands
  if (!started_) {
    started_ = true;
    enter(MotionState::kStand, stand_, sensors, last, tick);
  }

  take_request();         // 1. requests
  note_fall(fall, tick);  // 2. falls, detected or predicted

  // 3. Transitions and the active engine.
  switch (state_) {
    case MotionState::kStand:
      if (stand_.done() && want_script_ >= 0) {
        const int index = want_script_;
        want_script_ = -1;
        if (start_script(index, want_script_name_.data(), sensors, last, tick)) {
          script_->step(sensors, tick, out);
          return;
        }
        ++refused_;
      } else if (stand_.done() && want_walk_) {
        enter(MotionState::kWalk, *walk_, sensors, last, tick);
        walk_->set_velocity(walk_vx_, walk_vy_, walk_vtheta_);
        walk_->step(sensors, tick, out);
        return;
      }
      stand_.step(sensors, tick, out);
      return;

    case MotionState::kWalk:
      if (walk_->done()) {
        if (!want_walk_) {
          enter(MotionState::kStand, stand_, sensors, last, tick);
          stand_.step(sensors, tick, out);
          return;
        }
        // A walk asked for again while the last one was stopping: it starts again from where
        // it stopped (without this the stopped walk would be stepped for ever).
        enter(MotionState::kWalk, *walk_, sensors, last, tick);
        walk_->set_velocity(walk_vx_, walk_vy_, walk_vtheta_);
      }
      walk_->step(sensors, tick, out);
      return;

    case MotionState::kScript:
      if (script_->done() || want_script_ == kStopScript) {
        if (want_script_ == kStopScript) want_script_ = -1;
        enter(MotionState::kStand, stand_, sensors, last, tick);
        stand_.step(sensors, tick, out);
        return;
      }
      script_->step(sensors, tick, out);
      return;

    case MotionState::kFallen:
      step_fallen(sensors, tick, fallen, last, out);
      return;

    case MotionState::kFalling:
      if (static_cast<double>(tick - falling_clear_since_) * period_s_ >=
          protection_.hold_time_s()) {  // it did not fall: stand up from the pose reached
        enter(MotionState::kStand, stand_, sensors, last, tick);
        stand_.step(sensors, tick, out);
        return;
      }
      protection_.command(falling_direction_, relaxed_, out);
      return;

    case MotionState::kGetUp:
      if (script_->done()) {
        if (fallen || script_->aborted()) {
          // A failed attempt (the roll is not one): the next one differs (see the header).
          if (playing_get_up_ != roll_to_front_) {
            ++failed_get_ups_;
            back_attempt_failed_ = playing_get_up_ == get_up_back_;
          } else {
            back_attempt_failed_ = false;
          }
          state_ = MotionState::kFallen;
          fallen_since_ = tick;
          moving_since_fall_ = tick;
          active_script_name_.fill(0);
          hold_soft(sensors, out);
        } else {
          failed_get_ups_ = 0;
          back_attempt_failed_ = false;
          enter(MotionState::kStand, stand_, sensors, last, tick);
          stand_.step(sensors, tick, out);
        }
        return;
      }
      script_->step(sensors, tick, out);
      return;
  }
}

}  // namespace stride::fw
