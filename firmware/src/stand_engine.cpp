// StandEngine implementation.
#include "stride/firmware/stand_engine.hpp"

#include <algorithm>
#include <cmath>

#include "stride/firmware/stand_pose.hpp"

namespace stride::fw {

StandEngine::StandEngine(ParameterStore& params, double period_s)
    : params_(&params),
      period_s_(period_s),
      ramp_time_(params.add_real("stand.ramp_time", 1.5, 0.2, 10.0, "s",
                                 "time to ramp from the current pose to the stand pose")),
      gain_(params.add_real("stand.gain", 30.0, 5.0, 100.0, "1",
                            "servo gain while standing (0-100, P register = 2.54 g)")),
      pose_(kStandPoseRad) {}

void StandEngine::start(const hal::SensorFrame& sensors, const hal::CommandFrame& last_sent,
                        hal::Tick tick) noexcept {
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const hal::ServoCommand& c = last_sent.servos[i];
    const double measured = sensors.servos[i].position_rad;
    // Continue from the last target if one was being held, else from the measured pose.
    double from = (c.torque_enable && std::isfinite(c.position_rad)) ? c.position_rad : measured;
    if (!std::isfinite(from)) from = pose_[i];
    from_[i] = from;
  }
  start_tick_ = tick;
  settled_ = false;
}

void StandEngine::step(const hal::SensorFrame& /*sensors*/, hal::Tick tick,
                       hal::CommandFrame& out) noexcept {
  const double ramp = params_->value(ramp_time_);
  const double t = static_cast<double>(tick - start_tick_) * period_s_;
  const double s = std::clamp(t / ramp, 0.0, 1.0);
  const double blend = s * s * (3.0 - 2.0 * s);  // smoothstep
  const double p_gain = gain_to_p_register(params_->value(gain_));
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    hal::ServoCommand& c = out.servos[i];
    c.position_rad = from_[i] + (pose_[i] - from_[i]) * blend;
    c.moving_speed_rad_s = 0.0;
    c.p_gain = p_gain;
    c.i_gain = 0.0;
    c.d_gain = 0.0;
    c.torque_limit = 1.0;
    c.torque_enable = true;
  }
  settled_ = s >= 1.0;
}

}  // namespace stride::fw
