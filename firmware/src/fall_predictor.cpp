// FallPredictor implementation (see the header for the rule and FALLING.md for the figures).
#include "stride/firmware/fall_predictor.hpp"

#include <algorithm>
#include <cmath>

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

FallPredictor::FallPredictor(ParameterStore& params) : params_(params) {
  tilt_ = params.add_real("fall.tilt_rad", 0.7, 0.2, 1.4, "rad",
                          "torso tilt beyond which any rotation away from upright is a fall");
  rate_ = params.add_real("fall.rate_rad_s", 3.0, 0.5, 20.0, "rad/s",
                          "rotation rate away from upright that is a fall when still upright");
  confirm_ticks_ =
      params.add({"fall.confirm_ticks", ParamType::kInt, 2, 1, 100, "ticks",
                  "ticks the fall rule must hold before a fall is predicted", false, false});
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

void FallPredictor::observe(const AttitudeEstimator& attitude) noexcept {
  if (!attitude.valid()) return;  // no usable reading yet
  // The predictor's angles are the up direction's projections on the torso's y-z and x-z
  // planes: they reach +-pi (lying face down or on the back), which the rule's upright arming
  // needs.
  const Eigen::Vector3d& u = attitude.up();
  roll_ = std::atan2(u.y(), u.z());    // leaning right: +y reads gravity
  pitch_ = std::atan2(-u.x(), u.z());  // leaning forward: -x reads gravity
  // Gyro x is the rate of roll, gyro y the rate of pitch (small-angle, torso frame).
  const Eigen::Vector3d& g = attitude.gyro();

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
