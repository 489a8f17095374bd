// Tests of the identified MX servo (mx_servo.hpp) and its bench (servo_bench.hpp) against the
// measured MX-106 tables of ../shared/robot/servos.md (Rhoban BAM: pwm_mx106, velocity_mx106).
#include <gtest/gtest.h>

#include <cmath>

#include "stride/sim_hal/mx_servo.hpp"
#include "stride/sim_hal/servo_bench.hpp"

namespace stride::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct BlockedRow {
  double p, position_deg, target_deg, on_time_us;
};

// servos.md, "Measured duty cycles of an MX-106 whose output is held still, at 15 V".
constexpr BlockedRow kBlocked[] = {
    {5, 130.96, 120.41, 6.0},   {5, 130.96, 113.73, 10.0},  {5, 130.96, 103.97, 15.7},
    {5, 130.96, 93.08, 22.4},   {10, 130.96, 125.16, 6.6},  {10, 130.96, 118.39, 14.8},
    {10, 130.96, 110.74, 23.8}, {16, 130.96, 124.80, 11.5}, {16, 130.96, 118.48, 23.5}};

// servos.md, "Measured no-load speed of an MX-106 at full duty versus supply voltage".
constexpr double kNoLoadSpeed[] = {0.689, 1.106, 1.559, 1.989, 2.383, 2.809, 3.228,
                                   3.671, 4.107, 4.533, 4.983, 5.408, 5.844, 6.284};

TEST(MxServo, BlockedDutyMatchesTheMeasuredMx106Table) {
  for (const BlockedRow& row : kBlocked) {
    ServoBenchOptions o;
    o.experiment = BenchExperiment::kBlocked;
    o.voltage_v = 15.0;
    o.p_gain = row.p;
    o.error_deg = row.position_deg - row.target_deg;
    const ServoBenchResult r = run_servo_bench(o);
    const double measured = row.on_time_us / 42.7;
    EXPECT_LE(std::abs(r.duty - measured), std::max(0.05 * measured, 0.01))
        << "P " << row.p << " target " << row.target_deg << ": duty " << r.duty << " measured "
        << measured;
    // At rest the torque is the DC motor's kt (duty V - drop) / R.
    const MxServoParams p = mx_servo_params(fw::ServoModel::kMx106, 15.0);
    EXPECT_NEAR(r.torque_nm,
                p.torque_constant * (r.duty * 15.0 - p.driver_drop_v) / p.resistance_ohm, 1e-9);
  }
}

TEST(MxServo, NoLoadSpeedMatchesTheMeasuredMx106TableFrom3To15Volts) {
  for (int volts = 3; volts <= 15; ++volts) {
    ServoBenchOptions o;
    o.experiment = BenchExperiment::kNoLoad;
    o.voltage_v = volts;
    o.duration_s = 2.0;
    const double measured = kNoLoadSpeed[volts - 2];
    const double speed = run_servo_bench(o).speed_rad_s;
    EXPECT_LE(std::abs(speed - measured), 0.05 * measured)
        << volts << " V: " << speed << " rad/s, measured " << measured;
  }
}

TEST(MxServo, StiffnessGrowsWithPGainAndSupplyVoltage) {
  // Small blocked error: tau = kt (0.158 P e V - drop) / R; the slope is kt 0.158 P V / R.
  auto torque = [](double p_gain, double volts, double error_deg) {
    ServoBenchOptions o;
    o.experiment = BenchExperiment::kBlocked;
    o.p_gain = p_gain;
    o.voltage_v = volts;
    o.error_deg = error_deg;
    return run_servo_bench(o).torque_nm;
  };
  const MxServoParams p = mx_servo_params(fw::ServoModel::kMx106, 14.8);
  const double slope = (torque(32, 14.8, 2.0) - torque(32, 14.8, 1.0)) / (kPi / 180.0);
  EXPECT_NEAR(slope, p.torque_constant * 0.158 * 32 * 14.8 / p.resistance_ohm, 2.0);
  EXPECT_GT(torque(64, 14.8, 1.0), 1.9 * torque(32, 14.8, 1.0));
  EXPECT_GT(torque(32, 14.8, 1.0), torque(32, 12.0, 1.0));
}

TEST(MxServo, BackEmfDampsBelowSaturation) {
  MxServo servo;
  MxServoParams p = mx_servo_params(fw::ServoModel::kMx106, 14.8);
  p.backlash_rad = 0.0;
  servo.configure(p);
  servo.reset(0.0);
  servo.set_input({0.0, 0.0, 32.0, 1.0, true});
  servo.step(0.0, 1.0, 0.0, 1e-3);
  // On target, moving at 1 rad/s: the motor brakes with kt^2/R.
  EXPECT_NEAR(servo.output().motor_torque,
              -p.torque_constant * p.torque_constant / p.resistance_ohm, 1e-9);
  EXPECT_EQ(servo.output().duty, 0.0);
}

TEST(MxServo, FrictionHoldsAStillJointButNeverDrivesIt) {
  MxServo servo;
  servo.configure(mx_servo_params(fw::ServoModel::kMx106, 14.8));
  servo.reset(0.0);
  servo.set_input({0.0, 0.0, 32.0, 1.0, false});  // torque off
  // A still joint under a small external torque: friction cancels it exactly.
  EXPECT_NEAR(servo.step(0.0, 0.0, 0.05, 1e-3) + 0.05, 0.0, 1e-12);
  // A larger one: friction takes its budget off, the rest moves the joint.
  const double net = servo.step(0.0, 0.0, 2.0, 1e-3) + 2.0;
  EXPECT_GT(net, 1.5);
  EXPECT_LT(net, 2.0);
  // Moving slowly with no torque: friction at most stops the joint within the step.
  const double j = servo.params().armature_kg_m2, h = 1e-3, w = 1e-3;
  const double tau = servo.step(0.0, w, 0.0, h);
  EXPECT_LT(tau, 0.0);
  EXPECT_GE(w + h * tau / j, -1e-15);
}

TEST(MxServo, TorqueLimitScalesTheLargestDuty) {
  MxServo servo;
  servo.configure(mx_servo_params(fw::ServoModel::kMx64, 14.8));
  servo.reset(0.0);
  servo.set_input({1.0, 0.0, 32.0, 0.5, true});
  servo.step(0.0, 0.0, 0.0, 1e-3);
  EXPECT_NEAR(servo.output().duty, 0.5 * 0.9625, 1e-12);
}

TEST(MxServo, BacklashDelaysATorqueReversal) {
  MxServo servo;
  const MxServoParams p = mx_servo_params(fw::ServoModel::kMx106, 14.8);
  servo.configure(p);
  servo.reset(0.0);
  const double h = 1e-4;
  // Push positive until the gap is closed on the + side.
  servo.set_input({0.2, 0.0, 32.0, 1.0, true});
  for (int k = 0; k < 500; ++k) servo.step(0.0, 0.0, 0.0, h);
  EXPECT_DOUBLE_EQ(servo.backlash_gap(), 0.5 * p.backlash_rad);
  // Reverse: no motor torque reaches the output until the gap is crossed.
  servo.set_input({-0.2, 0.0, 32.0, 1.0, true});
  int crossing_steps = 0;
  while (servo.backlash_gap() > -0.5 * p.backlash_rad && crossing_steps < 10000) {
    servo.step(0.0, 0.0, 0.0, h);
    EXPECT_EQ(servo.output().joint_torque, servo.output().friction_torque);
    ++crossing_steps;
  }
  const double tau = std::abs(servo.output().motor_torque);
  const double expected_s = std::sqrt(2.0 * p.backlash_rad * p.armature_kg_m2 / tau);
  EXPECT_NEAR(crossing_steps * h, expected_s, 0.2 * expected_s);
  servo.step(0.0, 0.0, 0.0, h);
  EXPECT_LT(servo.output().joint_torque, -1.0);  // transmitted again
}

TEST(MxServo, PendulumFollowsASlowTrajectoryAndDropsWhenTorqueGoesOff) {
  ServoBenchOptions o;
  o.experiment = BenchExperiment::kPendulum;
  o.trajectory = BenchTrajectory::kLiftAndDrop;
  o.arm_length_m = 0.15;
  o.arm_mass_kg = 0.5;
  const ServoBenchResult r = run_servo_bench(o);
  ASSERT_EQ(r.trace.size(), 601u);
  const BenchSample& lifted = r.trace[195];  // 1.95 s: at the top, torque on
  EXPECT_NEAR(lifted.position, lifted.goal, 0.05);
  EXPECT_LT(lifted.position, -1.4);
  // Torque off at 2 s: the arm falls back past the bottom and comes to rest near it.
  EXPECT_GT(r.trace[250].position, -1.0);
  EXPECT_NEAR(r.trace.back().position, 0.0, 0.15);
  EXPECT_LT(std::abs(r.trace.back().speed), 0.5);
  // Deterministic: the same run twice gives the same trace.
  const ServoBenchResult again = run_servo_bench(o);
  EXPECT_EQ(again.trace.back().position, r.trace.back().position);
}

TEST(ServoBench, BadNamesAndRangesNameTheOptionAndWhatIsAllowed) {
  fw::ServoModel model;
  Status s = parse_servo_model("mx28", model);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(), "--model: unknown 'mx28' (allowed: mx64, mx106)");
  BenchTrajectory trajectory;
  s = parse_bench_trajectory("circle", trajectory);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("sin-time-square, lift-and-drop, up-and-down, sin-sin"),
            std::string::npos);
  ServoBenchOptions o;
  o.voltage_v = 40;
  s = validate(o);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message().rfind("--voltage: ", 0), 0u) << s.message();
  o.voltage_v = 12;
  o.p_gain = 300;
  EXPECT_EQ(validate(o).message().rfind("--p-gain: ", 0), 0u);
}

}  // namespace
}  // namespace stride::sim
