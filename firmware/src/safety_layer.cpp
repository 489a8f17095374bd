// SafetyLayer implementation.
#include "stride/firmware/safety_layer.hpp"

#include <algorithm>
#include <cmath>

namespace stride::fw {

SafetyLayer::SafetyLayer(ParameterStore& params, const ServoTable& servos)
    : params_(params), servos_(servos), predictor_(params) {
  max_torque_limit_ = params.add_real("safety.max_torque_limit", 1.0, 0.0, 1.0, "1",
                                      "upper bound of every servo's torque limit (fraction)");
  max_p_gain_ = params.add_real("safety.max_p_gain", 254.0, 0.0, 254.0, "1",
                                "upper bound of the P gain register sent to any servo");
  fall_tilt_ = params.add_real("safety.fall_tilt", 1.0, 0.3, 1.5, "rad",
                               "filtered torso tilt above which the robot counts as fallen");
  upright_tilt_ = params.add_real("safety.upright_tilt", 0.5, 0.1, 1.2, "rad",
                                  "filtered torso tilt below which the robot is upright again");
  fall_ticks_ =
      params.add({"safety.fall_ticks", ParamType::kInt, 10, 1, 1000, "ticks",
                  "ticks the tilt must stay above fall_tilt to declare a fall", false, false});
  error_ticks_ = params.add({"safety.error_ticks", ParamType::kInt, 50, 1, 100000, "ticks",
                             "consecutive ticks with error flags before torque-off", false, false});
  // Overheating, overload and input voltage by default; angle-limit and range errors are
  // transient consequences of a target and do not switch a servo off.
  error_mask_ = params.add(
      {"safety.error_mask", ParamType::kInt,
       hal::error_bits::kOverheating | hal::error_bits::kOverload | hal::error_bits::kInputVoltage,
       0, 127, "bits", "Dynamixel error bits that count as servo errors", false, false});
}

void SafetyLayer::observe(const hal::SensorFrame& sensors,
                          const AttitudeEstimator& attitude) noexcept {
  predictor_.observe(attitude);
  if (predictor_.falling() && !report_.falling) ++report_.predictions;
  report_.falling = predictor_.falling();
  report_.fall_direction = predictor_.direction();
  report_.fall_tilt_rad = predictor_.tilt_rad();
  const auto& a = sensors.cm730.accel_mps2;
  const double norm = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (!(norm > 1e-3) || !std::isfinite(norm)) return;  // no usable reading this tick
  const double tilt = std::acos(std::clamp(a[2] / norm, -1.0, 1.0));
  // First-order low-pass (about 5 ticks) so a kick's impact does not read as a fall.
  if (!tilt_initialised_) {
    report_.tilt_rad = tilt;
    tilt_initialised_ = true;
  } else {
    report_.tilt_rad += 0.2 * (tilt - report_.tilt_rad);
  }
  if (report_.tilt_rad > params_.value(fall_tilt_)) {
    ++tilt_run_;
  } else {
    tilt_run_ = 0;
  }
  if (!report_.fallen && tilt_run_ >= static_cast<std::uint32_t>(params_.value(fall_ticks_))) {
    report_.fallen = true;
    ++report_.falls;
  } else if (report_.fallen && report_.tilt_rad < params_.value(upright_tilt_)) {
    report_.fallen = false;
  }
}

void SafetyLayer::apply(const hal::SensorFrame& sensors, hal::CommandFrame& commands) noexcept {
  const double max_torque = params_.value(max_torque_limit_);
  const double max_p = params_.value(max_p_gain_);
  const auto error_mask = static_cast<std::uint8_t>(params_.value(error_mask_));
  const auto error_ticks = static_cast<std::uint32_t>(params_.value(error_ticks_));
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    hal::ServoCommand& c = commands.servos[i];
    const ServoSpec& spec = servos_[i];
    const hal::ServoState& s = sensors.servos[i];

    // Persistent error flags latch the servo off until reset_latches().
    if ((s.error_flags & error_mask) != 0) {
      if (++error_run_[i] >= error_ticks) report_.torque_off_latched[i] = true;
    } else {
      error_run_[i] = 0;
    }

    // NaN guard: hold the last safe target, or the measured position, or the limit centre.
    if (!std::isfinite(c.position_rad)) {
      ++report_.nan_targets[i];
      if (have_last_safe_[i]) {
        c.position_rad = last_safe_[i];
      } else if (std::isfinite(s.position_rad)) {
        c.position_rad = s.position_rad;
      } else {
        c.position_rad = 0.5 * (spec.min_rad + spec.max_rad);
      }
    }
    if (c.position_rad < spec.min_rad || c.position_rad > spec.max_rad) {
      ++report_.limit_clamps[i];
      c.position_rad = std::clamp(c.position_rad, spec.min_rad, spec.max_rad);
    }
    last_safe_[i] = c.position_rad;
    have_last_safe_[i] = true;

    if (!std::isfinite(c.moving_speed_rad_s) || c.moving_speed_rad_s < 0.0) {
      c.moving_speed_rad_s = 0.0;
    }
    const auto sane = [](double v, double lo, double hi) {
      return std::isfinite(v) ? std::clamp(v, lo, hi) : lo;
    };
    const double torque = sane(c.torque_limit, 0.0, max_torque);
    const double p_gain = sane(c.p_gain, 0.0, max_p);
    if (torque != c.torque_limit || p_gain != c.p_gain) ++report_.torque_clamps;
    c.torque_limit = torque;
    c.p_gain = p_gain;
    c.i_gain = sane(c.i_gain, 0.0, 254.0);
    c.d_gain = sane(c.d_gain, 0.0, 254.0);
    if (report_.torque_off_latched[i]) c.torque_enable = false;
  }
}

void SafetyLayer::reset_latches() noexcept {
  report_.torque_off_latched.fill(false);
  error_run_.fill(0);
}

}  // namespace stride::fw
