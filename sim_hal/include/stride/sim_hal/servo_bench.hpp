// ServoBench: one simulated MX servo on a bench like Rhoban BAM's (servos.md), for checking the
// servo model against measured tables: free output, blocked output, or a pendulum arm swinging
// under gravity on one of BAM's identification trajectories.
//
// Conventions (BAM's pendulum): angle 0 is the arm hanging down, positive counter-clockwise;
// the arm is a point mass m at length l, so the load inertia is m l^2 (plus the armature) and
// gravity applies -m g l sin(q). Integration: semi-implicit Euler at `step_s`.
#pragma once

#include <string>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/sim_hal/mx_servo.hpp"

namespace stride::sim {

enum class BenchExperiment { kNoLoad, kBlocked, kPendulum };
enum class BenchTrajectory { kSinTimeSquare, kLiftAndDrop, kUpAndDown, kSinSin };

struct ServoBenchOptions {
  fw::ServoModel model = fw::ServoModel::kMx106;
  MxFrictionModel friction = MxFrictionModel::kM6;
  BenchExperiment experiment = BenchExperiment::kNoLoad;
  double voltage_v = 15.0;     ///< supply (BAM's bench ran at 15 V)
  double p_gain = 32.0;        ///< P register
  double error_deg = 10.0;     ///< blocked: goal minus position [deg]
  double arm_length_m = 0.15;  ///< pendulum
  double arm_mass_kg = 0.5;    ///< pendulum point mass
  BenchTrajectory trajectory = BenchTrajectory::kSinTimeSquare;
  double duration_s = 6.0;
  double step_s = 0.0005;
  double sample_period_s = 0.01;  ///< trace rate
};

/// Parses the names used on the command line; the error names the option and what is allowed.
Status parse_servo_model(const std::string& text, fw::ServoModel& out);
Status parse_bench_experiment(const std::string& text, BenchExperiment& out);
Status parse_bench_trajectory(const std::string& text, BenchTrajectory& out);
Status parse_friction_model(const std::string& text, MxFrictionModel& out);
/// Range checks of the numeric options (voltage, P gain, error, arm, duration).
Status validate(const ServoBenchOptions& options);

/// Goal [rad] and torque enable of a trajectory at time t (BAM's definitions, 6 s each).
void bench_trajectory(BenchTrajectory trajectory, double t, double& goal, bool& enable);

struct BenchSample {
  double t = 0.0, goal = 0.0, position = 0.0, speed = 0.0, torque = 0.0;
};

struct ServoBenchResult {
  double speed_rad_s = 0.0;        ///< no-load: mean speed over the last 20 % of the run
  double duty = 0.0;               ///< blocked: PWM duty
  double torque_nm = 0.0;          ///< blocked: motor torque at the output
  std::vector<BenchSample> trace;  ///< pendulum (and no-load): sampled every sample_period_s
};

ServoBenchResult run_servo_bench(const ServoBenchOptions& options);

}  // namespace stride::sim
