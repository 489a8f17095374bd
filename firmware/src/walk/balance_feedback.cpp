// Gyro balance feedback (equations in balance_feedback.hpp).
#include "stride/firmware/walk/balance_feedback.hpp"

#include <algorithm>
#include <cmath>

namespace stride::fw::walk {
namespace {

double deadband(double value, double band) {
  if (std::abs(value) <= band) return 0.0;
  return value > 0.0 ? value - band : value + band;
}

}  // namespace

BalanceFeedback::BalanceFeedback(ParameterStore& store, double period_s)
    : store_(store), period_s_(period_s) {
  ankle_pitch_gain_ =
      store.add_real("walk.balance.ankle_pitch_gain", 0.461, 0.0, 1.0, "s",
                     "support ankle pitch added per rad/s of torso pitch rate (0: off)");
  ankle_roll_gain_ =
      store.add_real("walk.balance.ankle_roll_gain", 0.53, 0.0, 1.0, "s",
                     "support ankle roll added per rad/s of torso roll rate (0: off)");
  hip_pitch_gain_ =
      store.add_real("walk.balance.hip_pitch_gain", 0.49, 0.0, 1.0, "s",
                     "support hip pitch added per rad/s of torso pitch rate (0: off)");
  hip_roll_gain_ = store.add_real("walk.balance.hip_roll_gain", 0.925, 0.0, 1.0, "s",
                                  "support hip roll added per rad/s of torso roll rate (0: off)");
  filter_time_ = store.add_real("walk.balance.filter_time", 0.015, 0.0, 1.0, "s",
                                "low-pass time constant of the gyro feedback");
  deadband_ = store.add_real("walk.balance.deadband", 0.0, 0.0, 2.0, "rad/s",
                             "gyro rates below this are ignored");
  max_shift_ = store.add_real("walk.balance.max_shift", 0.516, 0.0, 1.0, "rad",
                              "largest joint shift the feedback may add");
}

void BalanceFeedback::reset() noexcept {
  gyro_x_ = 0.0;
  gyro_y_ = 0.0;
}

BalanceShift BalanceFeedback::update(const hal::Cm730State& imu) noexcept {
  const double gx = std::isfinite(imu.gyro_rad_s[0]) ? imu.gyro_rad_s[0] : 0.0;
  const double gy = std::isfinite(imu.gyro_rad_s[1]) ? imu.gyro_rad_s[1] : 0.0;
  const double alpha = period_s_ / (period_s_ + store_.value(filter_time_));
  gyro_x_ += alpha * (gx - gyro_x_);
  gyro_y_ += alpha * (gy - gyro_y_);
  const double band = store_.value(deadband_);
  const double limit = store_.value(max_shift_);
  const double rx = deadband(gyro_x_, band);
  const double ry = deadband(gyro_y_, band);
  auto shift = [&](ParamHandle gain, double rate) {
    return std::clamp(store_.value(gain) * rate, -limit, limit);
  };
  return {shift(ankle_pitch_gain_, ry), shift(ankle_roll_gain_, rx), shift(hip_pitch_gain_, ry),
          shift(hip_roll_gain_, rx)};
}

}  // namespace stride::fw::walk
