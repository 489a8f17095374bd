// MxServo: the identified MX servo law (firmware P-to-duty, DC motor, friction budget, backlash).
// Figures: the MX motor table (fw::mx_motor, kt, R, armature) and BAM's published friction
// parameters (../shared/robot/servos.md; see mx_servo.hpp).
#include "stride/sim_hal/mx_servo.hpp"

#include <algorithm>
#include <cmath>

#include "stride/sim_hal/servo_model.hpp"  // quantise_encoder, kMaxMovingSpeedRadS

namespace stride::sim {
namespace {

double sign(double x) {
  return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0);
}

}  // namespace

double MxServoParams::stall_torque_nm() const {
  return strength * torque_constant * std::max(0.0, max_duty * supply_voltage_v - driver_drop_v) /
         resistance_ohm;
}

double MxServoParams::no_load_speed_rad_s() const {
  return std::max(0.0, max_duty * supply_voltage_v - driver_drop_v) / torque_constant;
}

MxServoParams mx_servo_params(fw::ServoModel model, double supply_voltage_v,
                              MxFrictionModel friction) {
  MxServoParams p;
  p.supply_voltage_v = supply_voltage_v;
  MxFriction& f = p.friction;
  const bool mx64 = model == fw::ServoModel::kMx64;
  const fw::MxMotor& motor = fw::mx_motor(model);
  if (friction == MxFrictionModel::kM1) {
    // BAM params mx64/m1.json and mx106/m1.json.
    p.torque_constant = motor.m1.torque_constant;
    p.resistance_ohm = motor.m1.resistance_ohm;
    p.armature_kg_m2 = motor.m1.armature_kg_m2;
    f.base_nm = mx64 ? 0.0903868 : 0.1035203;
    f.viscous_nm_s = mx64 ? 0.0116916 : 0.0352024;
    return p;
  }
  // BAM M6 (servos.md table); the motor's figures from the MX motor table, friction here.
  p.torque_constant = motor.m6.torque_constant;
  p.resistance_ohm = motor.m6.resistance_ohm;
  p.armature_kg_m2 = motor.m6.armature_kg_m2;
  f.base_nm = mx64 ? 6.2179e-7 : 1.02325e-5;
  f.stribeck_nm = mx64 ? 0.1226953 : 0.1219541;
  f.stribeck_speed_rad_s = mx64 ? 2.5752774 : 1.7463252;
  f.stribeck_alpha = mx64 ? 0.8409018 : 1.1428278;
  f.viscous_nm_s = mx64 ? 0.0253370 : 0.0507157;
  f.load_motor = mx64 ? 0.3114720 : 0.1980055;
  f.load_external = mx64 ? 2.0462e-8 : 0.0222155;
  f.load_motor_stribeck = mx64 ? 0.1877438 : 0.1985997;
  f.load_external_stribeck = mx64 ? 0.0140659 : 0.0871033;
  f.load_motor_quadratic = mx64 ? 0.0069085 : 0.0099999;
  f.load_external_quadratic = mx64 ? 0.0099999 : 7.3269e-5;
  return p;
}

void MxServo::reset(double q) {
  setpoint_ = q;
  input_.goal_rad = q;
  output_ = {};
  gap_ = 0.0;
  gap_speed_ = 0.0;
  temperature_c_ = params_.ambient_temperature_c;
}

double MxServo::friction_budget(double tau_m, double tau_e, double w) const {
  const MxFriction& f = params_.friction;
  const double stribeck =
      std::exp(-std::pow(std::abs(w / f.stribeck_speed_rad_s), f.stribeck_alpha));
  double budget = f.base_nm + std::abs(f.load_external * tau_e - f.load_motor * tau_m);
  budget += stribeck * (f.stribeck_nm +
                        std::abs(f.load_external_stribeck * tau_e - f.load_motor_stribeck * tau_m));
  // Quadratic load terms, only when the motor and the load push against each other: the
  // larger of the two decides which side drives the gearbox.
  if (sign(tau_e) != sign(tau_m)) {
    if (std::abs(tau_e) < std::abs(tau_m))
      budget += stribeck * f.load_external_quadratic * tau_e * tau_e;
    else if (std::abs(tau_e) > std::abs(tau_m))
      budget += stribeck * f.load_motor_quadratic * tau_m * tau_m;
  }
  return budget + f.viscous_nm_s * std::abs(w);
}

double MxServo::step(double q, double w, double tau_e, double h, double joint_inertia) {
  const MxServoParams& p = params_;
  // 1. Moving speed on the set-point.
  const double speed = std::clamp(input_.moving_speed_rad_s, 0.0, kMaxMovingSpeedRadS);
  if (speed <= 0.0) {
    setpoint_ = input_.goal_rad;
  } else {
    const double max_move = speed * h;
    setpoint_ += std::clamp(input_.goal_rad - setpoint_, -max_move, max_move);
  }
  // 2.-3. Firmware duty and the DC motor.
  double duty = 0.0, tau_m = 0.0;
  if (input_.torque_enable) {
    const double largest = p.max_duty * std::clamp(input_.torque_limit, 0.0, 1.0);
    duty = std::clamp(
        p.error_gain * std::clamp(input_.p_gain, 0.0, 254.0) * (setpoint_ - quantise_encoder(q)),
        -largest, largest);
    const double applied = duty * p.supply_voltage_v;
    const double volts = sign(applied) * std::max(0.0, std::abs(applied) - p.driver_drop_v);
    tau_m = p.strength * p.torque_constant * (volts - p.torque_constant * w) / p.resistance_ohm;
  }
  // 5. Backlash: the motor torque reaches the output once the gap is closed on its side.
  const double half_gap = 0.5 * p.backlash_rad;
  double transmitted = tau_m;
  if (half_gap > 0.0 && tau_m != 0.0 && std::abs(gap_ - sign(tau_m) * half_gap) > 0.0) {
    transmitted = 0.0;
    gap_speed_ += h * tau_m / std::max(p.armature_kg_m2, 1e-9);
    gap_ += h * gap_speed_;
    if (std::abs(gap_) >= half_gap) {
      gap_ = std::copysign(half_gap, gap_);
      gap_speed_ = 0.0;
    }
  } else {
    gap_speed_ = 0.0;
  }
  // 4. Friction: the torque that stops the joint within h, clipped to the budget.
  const double inertia = std::max(joint_inertia, p.armature_kg_m2);
  const double stop = inertia / h * w + transmitted + tau_e;
  const double budget = friction_budget(tau_m, tau_e, w);
  const double friction = -sign(stop) * std::min(std::abs(stop), budget);
  double joint_tau = transmitted + friction;
  // 6. End stops.
  if (p.limited) {
    if (q > p.upper)
      joint_tau -= p.stop_stiffness * (q - p.upper) + p.stop_damping * std::max(w, 0.0);
    if (q < p.lower)
      joint_tau += p.stop_stiffness * (p.lower - q) - p.stop_damping * std::min(w, 0.0);
  }
  const double stall = p.stall_torque_nm();
  const double rel = stall > 0.0 ? tau_m / stall : 0.0;
  const double target_temp = p.ambient_temperature_c + p.thermal_rise_c * rel * rel;
  temperature_c_ += (target_temp - temperature_c_) * std::min(1.0, h / p.thermal_time_constant_s);
  output_ = {duty, tau_m, friction, joint_tau};
  return joint_tau;
}

double MxServo::load() const {
  const double stall = params_.stall_torque_nm();
  return stall > 0.0 ? std::clamp(output_.motor_torque / stall, -1.0, 1.0) : 0.0;
}

}  // namespace stride::sim
