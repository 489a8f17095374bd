// FallPredictor implementation (see the header for the rule and FALLING.md for the figures).
#include "stride/firmware/fall_predictor.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stride::fw {

const char* to_string(FallDirection direction) {
  switch (direction) {
    case FallDirection::kNone:
      return "none";
    case FallDirection::kForward:
      return "forward";
    case FallDirection::kBackward:
      return "backward";
    case FallDirection::kLeft:
      return "left";
    case FallDirection::kRight:
      return "right";
  }
  return "?";
}

FallPredictor::FallPredictor(ParameterStore& params, double period_s)
    : params_(params), period_s_(period_s) {
  tilt_ = params.add_real("fall.tilt_rad", 0.7, 0.2, 1.4, "rad",
                          "torso tilt beyond which any rotation away from upright is a fall");
  rate_ = params.add_real("fall.rate_rad_s", 3.0, 0.5, 20.0, "rad/s",
                          "rotation rate away from upright that is a fall when still upright");
  confirm_ticks_ =
      params.add({"fall.confirm_ticks", ParamType::kInt, 2, 1, 100, "ticks",
                  "ticks the fall rule must hold before a fall is predicted", false, false});
  accel_weight_ = params.add_real("fall.accel_weight", 0.02, 0.0, 1.0, "1",
                                  "per tick pull of the attitude towards the accelerometer");
  upright_ = params.add_real("fall.upright_rad", 0.3, 0.05, 1.0, "rad",
                             "roll and pitch below which the torso is upright (arms the rule)");
}

namespace {
/// One axis of the rule: the score (>= 1 is falling) of an angle and its rate.
double fall_score(double angle, double rate, double tilt_limit, double rate_limit) {
  const bool away = angle * rate > 0.0;  // rotating further from upright
  if (!away) return 0.0;
  return std::abs(angle) / tilt_limit + std::abs(rate) / rate_limit;
}
}  // namespace

double FallPredictor::tilt_rad() const noexcept {
  return std::max(std::abs(roll_), std::abs(pitch_));
}

void FallPredictor::observe(const hal::Cm730State& imu) noexcept {
  const auto& a = imu.accel_mps2;
  const auto& g = imu.gyro_rad_s;
  if (!std::isfinite(a[0]) || !std::isfinite(a[1]) || !std::isfinite(a[2]) ||
      !std::isfinite(g[0]) || !std::isfinite(g[1]))
    return;                                            // no usable reading this tick
  const double accel_roll = std::atan2(a[1], a[2]);    // leaning right: +y reads gravity
  const double accel_pitch = std::atan2(-a[0], a[2]);  // leaning forward: -x reads gravity
  if (!initialised_) {
    roll_ = accel_roll;
    pitch_ = accel_pitch;
    initialised_ = true;
  }
  const double w = params_.value(accel_weight_);
  // Gyro x is the rate of roll, gyro y the rate of pitch (small-angle, torso frame).
  roll_ += g[0] * period_s_;
  pitch_ += g[1] * period_s_;
  roll_ += w * (std::remainder(accel_roll - roll_, 2.0 * std::numbers::pi));
  pitch_ += w * (std::remainder(accel_pitch - pitch_, 2.0 * std::numbers::pi));

  const double tilt = params_.value(tilt_);
  const double rate = params_.value(rate_);
  const double pitch_score = fall_score(pitch_, g[1], tilt, rate);
  const double roll_score = fall_score(roll_, g[0], tilt, rate);
  const bool rule = pitch_score >= 1.0 || roll_score >= 1.0;
  run_ = rule ? run_ + 1 : 0;
  const double upright = params_.value(upright_);
  if (std::abs(roll_) < upright && std::abs(pitch_) < upright) armed_ = true;
  if (!falling_ && armed_ && run_ >= static_cast<std::uint32_t>(params_.value(confirm_ticks_))) {
    falling_ = true;
    armed_ = false;
    direction_ = pitch_score >= roll_score
                     ? (pitch_ > 0.0 ? FallDirection::kForward : FallDirection::kBackward)
                     : (roll_ > 0.0 ? FallDirection::kRight : FallDirection::kLeft);
  } else if (falling_ && run_ == 0) {
    falling_ = false;
  }
}

}  // namespace stride::fw
