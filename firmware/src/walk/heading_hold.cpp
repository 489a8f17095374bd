// Heading hold of the walk (equations in heading_hold.hpp).
#include "stride/firmware/walk/heading_hold.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace stride::fw::walk {

HeadingHold::HeadingHold(ParameterStore& store, double period_s, std::string_view prefix)
    : store_(store), period_s_(period_s), magnetic_(store, period_s, prefix) {
  const std::string p(prefix);
  gain_ = store.add_real(p + ".balance.heading_gain", 0.5, 0.0, 2.0, "1/step",
                         "turn velocity (rad/step) added per rad of heading error while no turn "
                         "is commanded (0: heading hold off)");
  rate_gain_ = store.add_real(p + ".balance.heading_rate_gain", 0.0, 0.0, 2.0, "s/step",
                              "turn velocity (rad/step) added per rad/s of filtered yaw rate "
                              "while no turn is commanded (0: off)");
  filter_time_ = store.add_real(p + ".balance.heading_filter_time", 0.5, 0.0, 5.0, "s",
                                "low-pass time constant of the yaw rate the rate term uses");
  max_correction_ = store.add_real(p + ".balance.heading_max_correction", 0.3, 0.0, 0.5, "rad/step",
                                   "largest turn velocity the heading hold may add to a step");
}

void HeadingHold::reset() noexcept {
  bias_sum_ = 0.0;
  bias_samples_ = 0;
  error_ = 0.0;
  rate_ = 0.0;
  holding_ = false;
  window_sum_ = 0.0;
  window_ticks_ = 0;
  previous_mean_ = step_pair_mean_ = 0.0;
  previous_mean_valid_ = false;
  magnetic_.reset();
  using_magnetometer_ = false;
  reference_valid_ = false;
  reference_ = 0.0;
}

void HeadingHold::update(const AttitudeEstimator& attitude, const hal::Cm730State& imu,
                         bool calibrating, bool hold) noexcept {
  const double yaw_rate = attitude.vertical_rate();
  using_magnetometer_ = magnetic_.active(imu);
  if (using_magnetometer_) magnetic_.update(attitude, imu, calibrating);
  if (calibrating) {
    bias_sum_ += yaw_rate;
    ++bias_samples_;
    return;
  }
  const double rate = yaw_rate - bias();
  const double alpha = period_s_ / (period_s_ + store_.value(filter_time_));
  rate_ += alpha * (rate - rate_);
  holding_ = hold;
  if (hold && using_magnetometer_) {
    if (!reference_valid_) reference_ = magnetic_.heading();
    reference_valid_ = true;
    error_ = magnetic_.heading() - reference_;
    window_sum_ += error_;
    ++window_ticks_;
  } else if (hold) {
    error_ += rate * period_s_;
    window_sum_ += error_;
    ++window_ticks_;
  } else {
    error_ = 0.0;
    reference_valid_ = false;
    window_sum_ = 0.0;
    window_ticks_ = 0;
    previous_mean_valid_ = false;
  }
}

double HeadingHold::begin_step() noexcept {
  if (window_ticks_ > 0) {
    const double mean = window_sum_ / window_ticks_;
    // The torso yaws to and fro once per step pair: the mean over the last two steps is free
    // of that swing (one step alone would keep half of it, of opposite sign left and right).
    step_pair_mean_ = previous_mean_valid_ ? 0.5 * (mean + previous_mean_) : mean;
    previous_mean_ = mean;
    previous_mean_valid_ = true;
  } else {
    step_pair_mean_ = 0.0;
  }
  window_sum_ = 0.0;
  window_ticks_ = 0;
  const double gain = store_.value(gain_);
  const double rate_gain = store_.value(rate_gain_);
  if (!holding_ || (gain == 0.0 && rate_gain == 0.0)) return 0.0;
  const double limit = store_.value(max_correction_);
  return std::clamp(-gain * step_pair_mean_ - rate_gain * rate_, -limit, limit);
}

}  // namespace stride::fw::walk
