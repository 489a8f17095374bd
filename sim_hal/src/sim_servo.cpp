// The two servo laws behind SimServo (see sim_servo.hpp).
#include "stride/sim_hal/sim_servo.hpp"

#include "stride/sim_hal/mx_servo.hpp"
#include "stride/sim_hal/physics_engine.hpp"
#include "stride/sim_hal/servo_model.hpp"

namespace stride::sim {

namespace {

/// The seed's law: a P controller on the torque-speed line with viscous and Coulomb friction.
class SeedServo final : public SimServo {
 public:
  double armature(fw::ServoModel model, double voltage, const ServoOptions& o) const override {
    const MotorCurve curve = motor_curve(model, voltage);
    return o.rotor_inertia_kg_m2 * curve.gear_ratio * curve.gear_ratio;
  }
  void reset(const ServoSetup& s, double q, const hal::ServoCommand& hold) override {
    const MotorCurve curve = motor_curve(s.model, s.supply_voltage_v);
    ServoParams p;
    p.stall_torque_nm = curve.stall_torque_nm * s.strength;
    p.no_load_speed_rad_s = curve.no_load_speed_rad_s;
    p.kp_per_register = s.options->kp_per_register;
    p.viscous_friction = s.options->viscous_friction * s.friction_scale;
    p.coulomb_friction = s.options->coulomb_friction * s.friction_scale;
    p.reflected_inertia = s.options->rotor_inertia_kg_m2 * curve.gear_ratio * curve.gear_ratio;
    p.limited = s.joint->limited;
    p.lower = s.joint->lower;
    p.upper = s.joint->upper;
    servo_.configure(p);
    servo_.reset(q);
    servo_.set_input({hold.position_rad, 0.0, hold.p_gain, hold.torque_limit, true});
  }
  void set_command(const hal::ServoCommand& c, bool enabled) override {
    servo_.set_input({c.position_rad, c.moving_speed_rad_s, c.p_gain, c.torque_limit, enabled});
  }
  double step(double q, double w, double h) override {
    last_torque_ = servo_.step(q, w, h);
    return last_torque_;
  }
  double load() const override { return servo_.load(); }
  double motor_torque_nm() const override { return last_torque_; }
  double temperature_c() const override { return servo_.temperature_c(); }
  std::uint64_t hash(std::uint64_t seed) const override {
    const double sp = servo_.setpoint();
    return fnv1a(seed, &sp, sizeof sp);
  }

 private:
  ServoModel servo_;
  double last_torque_ = 0.0;  ///< the last step's torque [N m]
};

/// The identified MX law (mx_servo.hpp).
class IdentifiedServo final : public SimServo {
 public:
  double armature(fw::ServoModel model, double voltage, const ServoOptions& o) const override {
    return mx_servo_params(model, voltage, o.friction_model).armature_kg_m2;
  }
  void reset(const ServoSetup& s, double q, const hal::ServoCommand& hold) override {
    MxServoParams mx = mx_servo_params(s.model, s.supply_voltage_v, s.options->friction_model);
    mx.strength = s.strength;
    if (s.friction_scale != 1.0) mx.friction.scale(s.friction_scale);
    mx.backlash_rad = s.options->backlash_rad;
    mx.driver_drop_v = s.options->driver_drop_v;
    mx.limited = s.joint->limited;
    mx.lower = s.joint->lower;
    mx.upper = s.joint->upper;
    servo_.configure(mx);
    servo_.reset(q);
    last_torque_ = 0.0;
    servo_.set_input({hold.position_rad, 0.0, hold.p_gain, hold.torque_limit, true});
  }
  void set_command(const hal::ServoCommand& c, bool enabled) override {
    servo_.set_input({c.position_rad, c.moving_speed_rad_s, c.p_gain, c.torque_limit, enabled});
  }
  double step(double q, double w, double h) override {
    // External torque on the joint: quasi-static, what balanced the servo's torque over the
    // last step. (A finite-difference estimate, J dw/h - tau, adds the step-to-step noise of w
    // to the friction's stopping torque and drove a 1/(2h) limit cycle of the whole body:
    // 0.5 m/s^2 of torso chatter standing still, at any step size.)
    last_torque_ = servo_.step(q, w, -last_torque_, h);
    return last_torque_;
  }
  double load() const override { return servo_.load(); }
  double motor_torque_nm() const override { return servo_.output().motor_torque; }
  double temperature_c() const override { return servo_.temperature_c(); }
  std::uint64_t hash(std::uint64_t seed) const override {
    const double sp = servo_.setpoint();
    const double gap = servo_.backlash_gap();
    return fnv1a(fnv1a(seed, &sp, sizeof sp), &gap, sizeof gap);
  }

 private:
  MxServo servo_;
  double last_torque_ = 0.0;  ///< the last step's joint torque [N m]
};

}  // namespace

std::unique_ptr<SimServo> make_sim_servo(ServoLaw law) {
  if (law == ServoLaw::kSeed) return std::make_unique<SeedServo>();
  return std::make_unique<IdentifiedServo>();
}

}  // namespace stride::sim
