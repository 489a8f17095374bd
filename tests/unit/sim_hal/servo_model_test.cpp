// Tests of the MX servo model on its own (igus.md 6.1): set-point, saturation, friction.
#include <gtest/gtest.h>

#include <cmath>

#include "stride/sim_hal/servo_model.hpp"

namespace stride::sim {
namespace {

/// Integrates one joint of inertia j driven by the servo (semi-explicit Euler, step h).
struct OneJoint {
  ServoModel servo;
  double q = 0.0, w = 0.0, j = 0.01, h = 0.0005;
  void run(double seconds) {
    for (int k = 0; k < static_cast<int>(std::lround(seconds / h)); ++k) {
      w += h * servo.step(q, w, h) / j;
      q += h * w;
    }
  }
};

ServoParams mx106() {
  ServoParams p;
  const MotorCurve c = motor_curve(fw::ServoModel::kMx106, 14.8);
  p.stall_torque_nm = c.stall_torque_nm;
  p.no_load_speed_rad_s = c.no_load_speed_rad_s;
  p.reflected_inertia = 6e-8 * c.gear_ratio * c.gear_ratio;
  return p;
}

TEST(ServoModel, MotorCurveFollowsTheEmanualFigures) {
  EXPECT_NEAR(motor_curve(fw::ServoModel::kMx106, 14.8).stall_torque_nm, 10.0, 1e-12);
  EXPECT_NEAR(motor_curve(fw::ServoModel::kMx106, 12.0).no_load_speed_rad_s, 45 * 2 * M_PI / 60,
              1e-12);
  EXPECT_NEAR(motor_curve(fw::ServoModel::kMx64, 14.8).stall_torque_nm, 7.3, 1e-12);
  EXPECT_NEAR(motor_curve(fw::ServoModel::kMx64, 13.4).stall_torque_nm, 6.65, 1e-9);  // midway
  EXPECT_EQ(motor_curve(fw::ServoModel::kMx64, 12).gear_ratio, 200.0);
  EXPECT_EQ(motor_curve(fw::ServoModel::kMx106, 12).gear_ratio, 225.0);
}

TEST(ServoModel, EncoderQuantisesTo4096TicksPerRevolution) {
  EXPECT_DOUBLE_EQ(quantise_encoder(0.0), 0.0);
  EXPECT_NEAR(quantise_encoder(0.001), kEncoderRadPerTick, 1e-15);
  EXPECT_NEAR(quantise_encoder(0.0007), 0.0, 1e-15);
  EXPECT_NEAR(quantise_encoder(1.0) / kEncoderRadPerTick, std::round(1.0 * 4096 / (2 * M_PI)),
              1e-9);
}

TEST(ServoModel, LargeStepSaturatesOnTheTorqueSpeedLine) {
  OneJoint joint;
  joint.servo.configure(mx106());
  joint.servo.reset(0.0);
  joint.servo.set_input({3.0, 0.0, 254.0, 1.0, true});  // far goal, no speed control
  // At rest the motor gives its stall torque.
  joint.servo.step(0.0, 0.0, joint.h);
  EXPECT_NEAR(joint.servo.motor_torque(), 10.0, 1e-9);
  joint.run(0.3);
  // Terminal speed where the torque-speed line meets viscous plus Coulomb friction:
  // ts (1 - w/w0) = b w + c.
  const ServoParams p = mx106();
  const double terminal = (p.stall_torque_nm - p.coulomb_friction) /
                          (p.stall_torque_nm / p.no_load_speed_rad_s + p.viscous_friction);
  EXPECT_NEAR(joint.w, terminal, 0.01 * terminal);
  EXPECT_LT(joint.w, p.no_load_speed_rad_s);
  EXPECT_LE(std::abs(joint.servo.motor_torque()),
            p.stall_torque_nm * (1 - joint.w / p.no_load_speed_rad_s) + 1e-9);
}

TEST(ServoModel, TorqueLimitCapsTheMotorTorque) {
  ServoModel servo;
  servo.configure(mx106());
  servo.reset(0.0);
  servo.set_input({1.0, 0.0, 254.0, 0.25, true});
  servo.step(0.0, 0.0, 0.001);
  EXPECT_NEAR(servo.motor_torque(), 2.5, 1e-9);
  EXPECT_NEAR(servo.load(), 0.25, 1e-9);
  servo.set_input({1.0, 0.0, 254.0, 0.25, false});  // torque off: limp
  servo.step(0.0, 0.0, 0.001);
  EXPECT_EQ(servo.motor_torque(), 0.0);
}

TEST(ServoModel, StepResponseSettlesOnTheGoalWithPGainStiffness) {
  OneJoint joint;
  joint.servo.configure(mx106());
  joint.servo.reset(0.0);
  const double p_gain = 32.0;
  joint.servo.set_input({0.2, 0.0, p_gain, 1.0, true});
  joint.run(2.0);
  // No load: it settles within the Coulomb dead band c / Kp of the goal (plus one tick).
  const double kp = mx106().kp_per_register * p_gain;
  EXPECT_NEAR(joint.q, 0.2, mx106().coulomb_friction / kp + kEncoderRadPerTick);
  EXPECT_NEAR(joint.w, 0.0, 0.01);  // encoder quantisation leaves a tiny limit cycle
  // The steady error under a constant load is load / Kp (P control, no integral).
  OneJoint loaded = joint;
  ServoModel& servo = loaded.servo;
  double q = 0.2, w = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const double tau = servo.step(q, w, loaded.h) - 2.0;  // 2 N m external load
    w += loaded.h * tau / loaded.j;
    q += loaded.h * w;
  }
  EXPECT_NEAR(0.2 - q, 2.0 / kp, mx106().coulomb_friction / kp + 2 * kEncoderRadPerTick);
}

TEST(ServoModel, MovingSpeedLimitsTheSetpointRate) {
  ServoModel servo;
  servo.configure(mx106());
  servo.reset(0.0);
  servo.set_input({1.0, 0.5, 32.0, 1.0, true});                // 0.5 rad/s
  for (int k = 0; k < 1000; ++k) servo.step(0.0, 0.0, 0.001);  // 1 s
  EXPECT_NEAR(servo.setpoint(), 0.5, 1e-9);
  servo.set_input({1.0, 100.0, 32.0, 1.0, true});  // above the register's maximum
  servo.step(0.0, 0.0, 0.01);
  EXPECT_NEAR(servo.setpoint(), 0.5 + kMaxMovingSpeedRadS * 0.01, 1e-9);
  servo.set_input({-1.0, 0.0, 32.0, 1.0, true});  // 0 = no speed control: jump
  servo.step(0.0, 0.0, 0.001);
  EXPECT_EQ(servo.setpoint(), -1.0);
}

TEST(ServoModel, EndStopPushesBackBeyondTheLimit) {
  ServoParams p = mx106();
  p.limited = true;
  p.lower = -1.0;
  p.upper = 1.0;
  ServoModel servo;
  servo.configure(p);
  servo.reset(1.0);
  servo.set_input({1.0, 0.0, 0.0, 1.0, false});
  EXPECT_LT(servo.step(1.1, 0.0, 0.001), -0.9 * p.stop_stiffness * 0.1);
  EXPECT_GT(servo.step(-1.1, 0.0, 0.001), 0.9 * p.stop_stiffness * 0.1);
  EXPECT_NEAR(servo.step(0.5, 0.0, 0.001), 0.0, 1e-12);
}

}  // namespace
}  // namespace stride::sim
