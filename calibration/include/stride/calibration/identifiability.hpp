// Identifiability of the calibration's values on a set of flight logs (issue 45 point 1):
// `stride calibrate --identifiability`, and the check that makes `stride calibrate --fit` refuse
// a set of values the logs cannot tell apart.
//
// The logs are replayed (log_replay.hpp, the calibration's windows) in the start world and in
// that world with one value moved by +-h (h: the value's fit step, calibration_parameters();
// whole values by one, one-sided at a bound), so that the sensitivity of every simulated sample
// to every value is a central finite difference around the start world. Each sample is divided
// by its channel's sensor noise (sensor_noise: the figures the servo and IMU models use), so that
// with D the matrix of scaled sensitivities the Fisher information is F = D^T D, the standard
// error of value i fitted together with the others sqrt((F^-1)_ii), and the correlation of two
// estimates (F^-1)_ij / sqrt((F^-1)_ii (F^-1)_jj). Channels: joint position, speed and load of
// every servo, gyro and accelerometer (the attitude is computed from the latter two and would
// count them twice). The noise is taken as white and independent per sample: the standard errors
// are lower bounds (model error, not sensor noise, dominates a real fit); the correlations say
// which values move the logs the same way, whatever the noise level.
//
// The log is cut into the routine's parts by the motion state each tick recorded: the stand
// before anything else, each script run (named after the routine's scripts when the log has as
// many as the routine, "script N" otherwise; firmware/scripts/IDENTIFICATION.md), the walk; the
// stand between parts counts to the part before it.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "stride/core/status.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/sim_hal/log_replay.hpp"
#include "stride/sim_hal/world_file.hpp"

namespace stride::calibration {

/// Standard deviation of one logged sample per channel: quantisation (LSB / sqrt(12)) and, for
/// the IMU, the chips' white noise over their noise bandwidth, averaged by the CM730.
struct SensorNoise {
  double position_rad = 0.0;
  double speed_rad_s = 0.0;
  double load = 0.0;  ///< fraction of the stall torque
  double gyro_rad_s = 0.0;
  double accel_mps2 = 0.0;
};
/// The figures of `world`'s servo and IMU models with their noise on (imu_model.hpp,
/// servo_model.hpp; the load register's unit, 1/1023 of the maximum, for the load).
SensorNoise sensor_noise(const sim::WorldOptions& world);

struct IdentifiabilityOptions {
  std::vector<std::string> names;  ///< values to analyse (parse_fit_names)
  sim::ReplayOptions replay;       ///< window length and threads, as the fit's
};

/// A value's errors and most correlated partner under one Fisher matrix.
struct ValueErrors {
  double standard_error = 0.0;  ///< fitted together with the others (value's unit)
  double alone_error = 0.0;     ///< fitted alone, the others known
  std::string partner;          ///< the value its estimate is most correlated with ("" alone)
  double correlation = 0.0;     ///< with that partner
};

struct ValueIdentifiability {
  std::string name;
  double step = 0.0;  ///< the reference change: the fit's step (calibration_parameters)
  /// sqrt of the chi-square a change of one step makes in each part of the routine (in units
  /// of the sensor noise: 1 is as large as one sample's noise), then over the whole log.
  std::vector<double> per_part;
  double total = 0.0;
  ValueErrors sensor;  ///< with the sensor noise
  ValueErrors floor;   ///< with the replay's error floor
};

struct IdentifiabilityResult {
  std::vector<std::string> parts;         ///< the routine's parts found in the logs
  std::vector<std::size_t> part_samples;  ///< compared ticks per part
  std::vector<ValueIdentifiability> values;
  Eigen::MatrixXd fisher;       ///< per step of each value (dimensionless), sensor noise
  Eigen::MatrixXd correlation;  ///< of the estimates
  /// The same with each channel group's noise raised to the RMS residual of the replays in the
  /// start world (the replay's own error: placement at each window's start, divergence, and
  /// whatever the start world gets wrong), which is what a fit sees as noise.
  Eigen::MatrixXd fisher_floor, correlation_floor;
  SensorNoise noise, floor;
  int replays = 0;
};

/// Analyses `options.names` on `logs` (checked by check_replayable and check_window) replayed in
/// `base` with `start` applied. Fails only if a world cannot be built.
Status analyse_identifiability(const std::vector<const fw::FlightLog*>& logs,
                               const sim::WorldOptions& base, const sim::WorldFile& start,
                               const IdentifiabilityOptions& options, IdentifiabilityResult& out);

struct ConfoundedPair {
  std::string first, second;
  double correlation = 0.0;
  bool floor = false;  ///< found with the replay's error floor (else with the sensor noise)
};
/// The pairs whose estimates correlate beyond `threshold` (|r|) with the sensor noise or with
/// the replay's error floor (the stronger of the two), the strongest first.
std::vector<ConfoundedPair> confounded_pairs(const IdentifiabilityResult& result, double threshold);
/// What would tell two values apart (a measurement instead of a fit, or a part of the routine).
std::string what_separates(const std::string& first, const std::string& second);

/// The table `stride calibrate --identifiability` prints.
std::string identifiability_table(const IdentifiabilityResult& result);

}  // namespace stride::calibration
