// Capture-point footstep and timing feedback (equations and sources in capture_step.hpp).
#include "stride/firmware/walk/capture_step.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace stride::fw::walk {
namespace {

constexpr double kGravity = 9.81;

}  // namespace

CaptureStep::CaptureStep(ParameterStore& store, double period_s, std::string_view prefix)
    : store_(store), period_s_(period_s) {
  const std::string p(prefix);
  step_gain_x_ = store.add_real(p + ".capture.step_gain_x", 0.0, 0.0, 3.0, "1",
                                "next footstep moved forward per m of capture-point deviation "
                                "(0: off)");
  step_gain_y_ = store.add_real(p + ".capture.step_gain_y", 0.0, 0.0, 3.0, "1",
                                "next footstep moved sideways per m of capture-point deviation "
                                "(0: off)");
  max_step_x_ = store.add_real(p + ".capture.max_step_x", 0.05, 0.0, 0.15, "m",
                               "largest forward or backward footstep correction");
  max_step_y_ = store.add_real(p + ".capture.max_step_y", 0.04, 0.0, 0.1, "m",
                               "largest sideways footstep correction");
  timing_gain_ = store.add_real(p + ".capture.timing_gain", 0.0, 0.0, 50.0, "1/m",
                                "phase rate change per m of lateral capture-point deviation "
                                "towards the swing side (0: off)");
  max_timing_ = store.add_real(p + ".capture.max_timing", 0.3, 0.0, 0.6, "1",
                               "largest relative change of the phase rate");
  com_height_ = store.add_real(p + ".capture.com_height", 0.42, 0.2, 0.7, "m",
                               "pendulum height of the capture-point estimate");
  learn_steps_ = store.add_real(p + ".capture.learn_steps", 4.0, 0.5, 50.0, "step pairs",
                                "time constant of the learned expected tilt per phase");
  rate_filter_time_ = store.add_real(p + ".capture.rate_filter_time", 0.05, 0.0, 1.0, "s",
                                     "low-pass time constant of the tilt deviation's rate");
  touchdown_load_ = store.add_real(p + ".capture.touchdown_load", 0.08, 0.0, 1.0, "1",
                                   "swing knee load (fraction of stall torque) that ends a step "
                                   "late in its phase (0: the clock ends every step)");
  touchdown_phase_ = store.add_real(p + ".capture.touchdown_phase", 0.7, 0.5, 1.0, "1",
                                    "earliest step phase a touchdown may end the step at");
}

void CaptureStep::reset() noexcept {
  tilt_valid_ = false;
  roll_ = pitch_ = 0.0;
  expected_roll_.fill(0.0);
  expected_pitch_.fill(0.0);
  previous_roll_dev_ = previous_pitch_dev_ = 0.0;
  roll_rate_ = pitch_rate_ = 0.0;
  xi_x_ = xi_y_ = 0.0;
}

bool CaptureStep::footstep_enabled() const noexcept {
  return store_.value(step_gain_x_) > 0.0 || store_.value(step_gain_y_) > 0.0;
}

bool CaptureStep::timing_enabled() const noexcept {
  return store_.value(timing_gain_) > 0.0;
}

void CaptureStep::update(const AttitudeEstimator& attitude, double pair_phase, double step_time,
                         bool walking, bool standing) noexcept {
  if (!attitude.valid()) return;
  roll_ = attitude.roll();
  pitch_ = attitude.pitch();
  if (!tilt_valid_) {
    expected_roll_.fill(roll_);
    expected_pitch_.fill(pitch_);
    tilt_valid_ = true;
  }
  // The expectation is piecewise linear over the bins (bin centres at (k + 0.5) / kBins), so
  // the deviation has no steps at the bin edges.
  const double u = std::clamp(pair_phase, 0.0, 1.0) * static_cast<double>(kBins) - 0.5;
  const double floor_u = std::floor(u);
  const double w = u - floor_u;
  const auto n = static_cast<long>(kBins);
  const auto k0 = static_cast<std::size_t>((static_cast<long>(floor_u) % n + n) % n);
  const std::size_t k1 = (k0 + 1) % kBins;
  const double expected_roll = (1.0 - w) * expected_roll_[k0] + w * expected_roll_[k1];
  const double expected_pitch = (1.0 - w) * expected_pitch_[k0] + w * expected_pitch_[k1];
  const double roll_dev = roll_ - expected_roll;
  const double pitch_dev = pitch_ - expected_pitch;
  if (standing) {
    // Standing: every phase expects the standing tilt (a short mean, 0.5 s).
    const double lambda = period_s_ / (period_s_ + 0.5);
    for (std::size_t k = 0; k < kBins; ++k) {
      expected_roll_[k] += lambda * (roll_ - expected_roll_[k]);
      expected_pitch_[k] += lambda * (pitch_ - expected_pitch_[k]);
    }
  } else if (walking && step_time > 0.0) {
    // Each bin is visited for 2T/kBins seconds per step pair; its mean spans learn_steps pairs.
    const double ticks_per_visit = 2.0 * step_time / (static_cast<double>(kBins) * period_s_);
    const double lambda =
        std::min(1.0, 1.0 / (std::max(1.0, ticks_per_visit) * store_.value(learn_steps_)));
    expected_roll_[k0] += lambda * (1.0 - w) * roll_dev;
    expected_roll_[k1] += lambda * w * roll_dev;
    expected_pitch_[k0] += lambda * (1.0 - w) * pitch_dev;
    expected_pitch_[k1] += lambda * w * pitch_dev;
  }
  const double alpha = period_s_ / (period_s_ + store_.value(rate_filter_time_));
  roll_rate_ += alpha * ((roll_dev - previous_roll_dev_) / period_s_ - roll_rate_);
  pitch_rate_ += alpha * ((pitch_dev - previous_pitch_dev_) / period_s_ - pitch_rate_);
  previous_roll_dev_ = roll_dev;
  previous_pitch_dev_ = pitch_dev;
  const double h = store_.value(com_height_);
  const double omega = std::sqrt(kGravity / h);
  xi_x_ = h * (pitch_dev + pitch_rate_ / omega);
  xi_y_ = -h * (roll_dev + roll_rate_ / omega);
}

double CaptureStep::step_offset_x() const noexcept {
  const double limit = store_.value(max_step_x_);
  return std::clamp(store_.value(step_gain_x_) * xi_x_, -limit, limit);
}

double CaptureStep::step_offset_y() const noexcept {
  const double limit = store_.value(max_step_y_);
  return std::clamp(store_.value(step_gain_y_) * xi_y_, -limit, limit);
}

double CaptureStep::phase_rate(bool left_swings) const noexcept {
  const double gain = store_.value(timing_gain_);
  if (!(gain > 0.0)) return 1.0;
  const double limit = store_.value(max_timing_);
  const double side = left_swings ? 1.0 : -1.0;
  return std::clamp(1.0 + gain * side * xi_y_, 1.0 - limit, 1.0 + limit);
}

}  // namespace stride::fw::walk

namespace stride::fw::walk {

bool CaptureStep::touchdown(double phase, double swing_knee_load) const noexcept {
  const double threshold = store_.value(touchdown_load_);
  return threshold > 0.0 && phase >= store_.value(touchdown_phase_) &&
         std::abs(swing_knee_load) >= threshold;
}

}  // namespace stride::fw::walk
