// Gyro balance feedback (equations in balance_feedback.hpp).
#include "stride/firmware/walk/balance_feedback.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace stride::fw::walk {
namespace {

double deadband(double value, double band) {
  if (std::abs(value) <= band) return 0.0;
  return value > 0.0 ? value - band : value + band;
}

}  // namespace

BalanceFeedback::BalanceFeedback(ParameterStore& store, double period_s, std::string_view prefix)
    : store_(store), period_s_(period_s) {
  const std::string p(prefix);
  ankle_pitch_gain_ =
      store.add_real(p + ".balance.ankle_pitch_gain", 0.3043, 0.0, 1.0, "s",
                     "support ankle pitch added per rad/s of torso pitch rate (0: off)");
  ankle_roll_gain_ =
      store.add_real(p + ".balance.ankle_roll_gain", 0.9589, 0.0, 1.0, "s",
                     "support ankle roll added per rad/s of torso roll rate (0: off)");
  hip_pitch_gain_ =
      store.add_real(p + ".balance.hip_pitch_gain", 0.3629, 0.0, 1.0, "s",
                     "support hip pitch added per rad/s of torso pitch rate (0: off)");
  hip_roll_gain_ = store.add_real(p + ".balance.hip_roll_gain", 0.0178, 0.0, 1.0, "s",
                                  "support hip roll added per rad/s of torso roll rate (0: off)");
  filter_time_ = store.add_real(p + ".balance.filter_time", 0.055, 0.0, 1.0, "s",
                                "low-pass time constant of the gyro feedback");
  deadband_ = store.add_real(p + ".balance.deadband", 0.1859, 0.0, 2.0, "rad/s",
                             "gyro rates below this are ignored");
  max_shift_ = store.add_real(p + ".balance.max_shift", 0.2711, 0.0, 1.0, "rad",
                              "largest joint shift the feedback may add");
  pitch_angle_gain_ =
      store.add_real(p + ".balance.pitch_angle_gain", 0.0, 0.0, 20.0, "1/s",
                     "torso pitch error (rad) added to the fed-back pitch rate (0: off)");
  roll_angle_gain_ =
      store.add_real(p + ".balance.roll_angle_gain", 0.0, 0.0, 20.0, "1/s",
                     "torso roll error (rad) added to the fed-back roll rate (0: off)");
  tilt_reference_time_ =
      store.add_real(p + ".balance.tilt_reference_time", 0.0, 0.0, 20.0, "s",
                     "time constant of the slow mean tilt the tilt term holds the torso to "
                     "(0: the tilt at the walk's start)");
  double_support_weight_ =
      store.add_real(p + ".balance.double_support_weight", 0.7912, 0.0, 1.0, "1",
                     "share of the feedback the swing leg takes while both feet are down");
  start_sway_steps_ =
      store.add_real(p + ".balance.start_sway_steps", 1.4887, 0.0, 10.0, "steps",
                     "steps over which the ZMP excursion ramps to full after the start (0: off)");
}

void BalanceFeedback::reset() noexcept {
  gyro_x_ = 0.0;
  gyro_y_ = 0.0;
  tilt_valid_ = false;
  roll_reference_ = pitch_reference_ = 0.0;
}

double BalanceFeedback::double_support_weight() const noexcept {
  return store_.value(double_support_weight_);
}

double BalanceFeedback::start_sway_scale(int step_count) const noexcept {
  const double steps = store_.value(start_sway_steps_);
  if (steps <= 0.0) return 1.0;
  return std::clamp(static_cast<double>(step_count) / steps, 0.0, 1.0);
}

BalanceShift BalanceFeedback::update(const AttitudeEstimator& attitude) noexcept {
  const double gx = attitude.gyro().x();
  const double gy = attitude.gyro().y();
  const double alpha = period_s_ / (period_s_ + store_.value(filter_time_));
  gyro_x_ += alpha * (gx - gyro_x_);
  gyro_y_ += alpha * (gy - gyro_y_);
  // Tilt: the attitude estimate; the reference is the accelerometer's tilt at the walk's first
  // tick with a reading (one sample, as the balance feedback's own filter started from).
  const double roll = attitude.roll(), pitch = attitude.pitch();
  if (!tilt_valid_ && attitude.valid()) {
    roll_reference_ = attitude.measured_roll();
    pitch_reference_ = attitude.measured_pitch();
    tilt_valid_ = true;
  }
  if (const double reference_time = store_.value(tilt_reference_time_); reference_time > 0.0) {
    const double gamma = period_s_ / (period_s_ + reference_time);
    roll_reference_ += gamma * (roll - roll_reference_);
    pitch_reference_ += gamma * (pitch - pitch_reference_);
  }
  const double band = store_.value(deadband_);
  const double limit = store_.value(max_shift_);
  const double rx =
      deadband(gyro_x_, band) + store_.value(roll_angle_gain_) * (roll - roll_reference_);
  const double ry =
      deadband(gyro_y_, band) + store_.value(pitch_angle_gain_) * (pitch - pitch_reference_);
  auto shift = [&](ParamHandle gain, double rate) {
    return std::clamp(store_.value(gain) * rate, -limit, limit);
  };
  return {shift(ankle_pitch_gain_, ry), shift(ankle_roll_gain_, rx), shift(hip_pitch_gain_, ry),
          shift(hip_roll_gain_, rx)};
}

}  // namespace stride::fw::walk
