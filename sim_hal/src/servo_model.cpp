// ServoModel: MX servo torque model (set-point, P control, torque-speed saturation, friction).
#include "stride/sim_hal/servo_model.hpp"

#include "stride/firmware/mx_motor.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace stride::sim {
namespace {

constexpr double kRpm = 2.0 * M_PI / 60.0;

/// Piecewise-linear through (v[i], y[i]), extrapolated with the end segments.
double interpolate(const std::array<double, 3>& v, const std::array<double, 3>& y, double x) {
  const int seg = x < v[1] ? 0 : 1;
  return y[seg] + (y[seg + 1] - y[seg]) * (x - v[seg]) / (v[seg + 1] - v[seg]);
}

}  // namespace

double quantise_encoder(double angle_rad) {
  return std::round(angle_rad / kEncoderRadPerTick) * kEncoderRadPerTick;
}

MotorCurve motor_curve(fw::ServoModel model, double voltage_v) {
  const fw::MxMotor& motor = fw::mx_motor(model);
  MotorCurve out;
  out.stall_torque_nm =
      std::max(0.0, interpolate(fw::kMxDatasheetVolts, motor.stall_torque_nm, voltage_v));
  out.no_load_speed_rad_s =
      std::max(1e-3, interpolate(fw::kMxDatasheetVolts, motor.no_load_speed_rpm, voltage_v) * kRpm);
  out.gear_ratio = motor.gear_ratio;
  return out;
}

void ServoModel::reset(double q) {
  setpoint_ = q;
  motor_torque_ = 0.0;
  temperature_c_ = params_.ambient_temperature_c;
  input_.goal_rad = q;
}

double ServoModel::step(double q, double w, double h) {
  const ServoParams& p = params_;
  // 1. Moving-speed limit on the set-point.
  const double goal = input_.goal_rad;
  const double speed = std::clamp(input_.moving_speed_rad_s, 0.0, kMaxMovingSpeedRadS);
  if (speed <= 0.0) {
    setpoint_ = goal;
  } else {
    const double max_move = speed * h;
    setpoint_ += std::clamp(goal - setpoint_, -max_move, max_move);
  }
  // 2.-3. P control on the encoder, saturated on the torque-speed line.
  double tau = 0.0;
  if (input_.torque_enable) {
    const double kp = p.kp_per_register * std::clamp(input_.p_gain, 0.0, 254.0);
    tau = kp * (setpoint_ - quantise_encoder(q));
    const double ts = p.stall_torque_nm;
    const double ratio = w / p.no_load_speed_rad_s;
    const double limit = std::clamp(input_.torque_limit, 0.0, 1.0) * ts;
    const double upper = std::min(limit, ts * (1.0 - ratio));
    const double lower = std::max(-limit, -ts * (1.0 + ratio));
    tau = upper < lower ? 0.5 * (upper + lower) : std::clamp(tau, lower, upper);
  }
  motor_torque_ = tau;
  // 4. Friction (viscous; Coulomb bounded by what stops the rotor within one step).
  // The explicit friction slope (viscous plus stiction) stays below J/h, so that one step can
  // at most stop the rotor, never reverse it (an over-damped explicit step chatters).
  double joint_tau = tau - p.viscous_friction * w;
  const double slope_left = std::max(0.0, p.reflected_inertia / h - p.viscous_friction);
  const double stiction = std::min(p.coulomb_friction, slope_left * std::abs(w));
  joint_tau -= std::copysign(stiction, w);
  // 5. End stops.
  if (p.limited) {
    if (q > p.upper)
      joint_tau -= p.stop_stiffness * (q - p.upper) + p.stop_damping * std::max(w, 0.0);
    if (q < p.lower)
      joint_tau += p.stop_stiffness * (p.lower - q) - p.stop_damping * std::min(w, 0.0);
  }
  // Thermal first-order model: heats with (tau / tau_s)^2.
  const double rel = p.stall_torque_nm > 0 ? tau / p.stall_torque_nm : 0.0;
  const double target_temp = p.ambient_temperature_c + p.thermal_rise_c * rel * rel;
  temperature_c_ += (target_temp - temperature_c_) * std::min(1.0, h / p.thermal_time_constant_s);
  return joint_tau;
}

double ServoModel::load() const {
  return params_.stall_torque_nm > 0
             ? std::clamp(motor_torque_ / params_.stall_torque_nm, -1.0, 1.0)
             : 0.0;
}

}  // namespace stride::sim
