// ServoBench: the one-servo bench experiments (no-load, blocked, pendulum; servos.md, BAM).
#include "stride/sim_hal/servo_bench.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace stride::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kGravity = 9.80665;

/// Cubic from (t0, x0) to (t1, x1) with zero speed at both ends.
double ease(double t, double t0, double x0, double t1, double x1) {
  if (t <= t0) return x0;
  if (t >= t1) return x1;
  const double s = (t - t0) / (t1 - t0);
  return x0 + (x1 - x0) * s * s * (3.0 - 2.0 * s);
}

template <typename Enum, std::size_t N>
Status parse_name(const std::string& text, const std::pair<const char*, Enum> (&names)[N],
                  const char* option, Enum& out) {
  std::string allowed;
  for (const auto& [name, value] : names) {
    if (text == name) {
      out = value;
      return Status::ok();
    }
    allowed += (allowed.empty() ? "" : ", ") + std::string(name);
  }
  return Status::error(std::string("--") + option + ": unknown '" + text +
                       "' (allowed: " + allowed + ")");
}

Status in_range(const char* option, double value, double lo, double hi, const char* unit) {
  if (value >= lo && value <= hi) return Status::ok();
  return Status::error(std::string("--") + option + ": " + std::to_string(value) +
                       " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) +
                       "] " + unit);
}

}  // namespace

Status parse_servo_model(const std::string& text, fw::ServoModel& out) {
  static constexpr std::pair<const char*, fw::ServoModel> kNames[] = {
      {"mx64", fw::ServoModel::kMx64}, {"mx106", fw::ServoModel::kMx106}};
  return parse_name(text, kNames, "model", out);
}

Status parse_bench_experiment(const std::string& text, BenchExperiment& out) {
  static constexpr std::pair<const char*, BenchExperiment> kNames[] = {
      {"no-load", BenchExperiment::kNoLoad},
      {"blocked", BenchExperiment::kBlocked},
      {"pendulum", BenchExperiment::kPendulum}};
  return parse_name(text, kNames, "experiment", out);
}

Status parse_bench_trajectory(const std::string& text, BenchTrajectory& out) {
  static constexpr std::pair<const char*, BenchTrajectory> kNames[] = {
      {"sin-time-square", BenchTrajectory::kSinTimeSquare},
      {"lift-and-drop", BenchTrajectory::kLiftAndDrop},
      {"up-and-down", BenchTrajectory::kUpAndDown},
      {"sin-sin", BenchTrajectory::kSinSin}};
  return parse_name(text, kNames, "trajectory", out);
}

Status parse_friction_model(const std::string& text, MxFrictionModel& out) {
  static constexpr std::pair<const char*, MxFrictionModel> kNames[] = {
      {"m1", MxFrictionModel::kM1}, {"m6", MxFrictionModel::kM6}};
  return parse_name(text, kNames, "friction", out);
}

Status validate(const ServoBenchOptions& o) {
  for (Status s : {in_range("voltage", o.voltage_v, 1.0, 24.0, "V"),
                   in_range("p-gain", o.p_gain, 0.0, 254.0, "(P register)"),
                   in_range("error-deg", o.error_deg, -180.0, 180.0, "deg"),
                   in_range("arm-length", o.arm_length_m, 0.01, 1.0, "m"),
                   in_range("arm-mass", o.arm_mass_kg, 0.0, 10.0, "kg"),
                   in_range("duration", o.duration_s, 0.01, 600.0, "s")})
    if (!s) return s;
  return Status::ok();
}

void bench_trajectory(BenchTrajectory trajectory, double t, double& goal, bool& enable) {
  enable = true;
  switch (trajectory) {
    case BenchTrajectory::kSinTimeSquare:
      goal = std::sin(t * t);
      return;
    case BenchTrajectory::kLiftAndDrop:
      goal = ease(t, 0.0, 0.0, 2.0, -kPi / 2);
      enable = t < 2.0;
      return;
    case BenchTrajectory::kUpAndDown:
      goal = t < 3.0 ? ease(t, 0.0, 0.0, 3.0, kPi / 2) : ease(t, 3.0, kPi / 2, 6.0, 0.4 * kPi);
      return;
    case BenchTrajectory::kSinSin:
      goal = std::sin(t) * kPi / 2 + std::sin(5.0 * t) * 0.5 * std::sin(2.0 * t);
      return;
  }
}

ServoBenchResult run_servo_bench(const ServoBenchOptions& o) {
  ServoBenchResult result;
  MxServo servo;
  MxServoParams params = mx_servo_params(o.model, o.voltage_v, o.friction);
  servo.configure(params);
  servo.reset(0.0);
  const double h = o.step_s;
  const long steps = std::lround(o.duration_s / h);
  const long sample_every = std::max(1L, std::lround(o.sample_period_s / h));

  if (o.experiment == BenchExperiment::kBlocked) {
    servo.set_input({o.error_deg * kPi / 180.0, 0.0, o.p_gain, 1.0, true});
    servo.step(0.0, 0.0, 0.0, h);
    result.duty = servo.output().duty;
    result.torque_nm = servo.output().motor_torque;
    return result;
  }

  const bool pendulum = o.experiment == BenchExperiment::kPendulum;
  const double load_inertia = pendulum ? o.arm_mass_kg * o.arm_length_m * o.arm_length_m : 0.0;
  const double inertia = load_inertia + params.armature_kg_m2;
  const long average_from = steps - steps / 5;
  double q = 0.0, w = 0.0, speed_sum = 0.0;
  long speed_count = 0;
  for (long k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) * h;
    double goal = 1e4;  // no-load: a goal far away keeps the duty saturated
    bool enable = true;
    if (pendulum) bench_trajectory(o.trajectory, t, goal, enable);
    servo.set_input({goal, 0.0, o.p_gain, 1.0, enable});
    const double gravity =
        pendulum ? -o.arm_mass_kg * kGravity * o.arm_length_m * std::sin(q) : 0.0;
    const double tau = servo.step(q, w, gravity, h, inertia) + gravity;
    if (k % sample_every == 0)
      result.trace.push_back(
          {t, pendulum ? goal : servo.setpoint(), q, w, servo.output().motor_torque});
    if (k >= average_from) {
      speed_sum += w;
      ++speed_count;
    }
    if (k == steps) break;
    w += h * tau / inertia;
    q += h * w;
  }
  result.speed_rad_s = speed_count > 0 ? speed_sum / static_cast<double>(speed_count) : 0.0;
  return result;
}

}  // namespace stride::sim
