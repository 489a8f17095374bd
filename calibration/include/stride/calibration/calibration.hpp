// Calibration of the simulated robot from flight logs (`stride calibrate`, issue 30 point 3).
//
// Two values are measured rather than fitted, because the servo readings cannot tell them apart
// from the MX-106 torque: a joint's deflection under the trunk's weight and its dynamics both go
// with m / (s V) (trunk mass m, torque scale s, supply V: the motor torque is duty x V x kt / R x
// s), and every leg servo is an MX-106. The supply voltage is read from the logs (the CM730
// measures it; logged_supply_voltage) and the trunk mass from the robot weighed on a scale
// (trunk_scale_for_mass, `--robot-mass`); fitting them is allowed but not identified.
//
// The replay error (log_replay.hpp) of the logs in a world is a function of the world's
// calibration (world_file.hpp: servo torque per model, friction, supply voltage, bus latency,
// trunk mass and centre of mass, IMU biases). The fit minimises
//
//   J = sum over windows of ticks_w * sum over channels c of (rms_c,w / scale_c)^2 / sum ticks_w
//
// with the channels and scales of kCalibrationChannels (roughly one sensor resolution each, so
// that every channel counts). The latency (whole ticks) is chosen by trying every value at the
// start and again around the fit. The IMU biases are fitted in closed form: a constant bias the
// world lacks leaves its value as the mean of the logged minus the simulated reading (the replay
// is open loop, so it moves nothing else), and a few such updates settle it. The other
// continuous values go to NLopt's BOBYQA (a bounded derivative-free trust-region method), which
// alone left the biases at their start: their few units of J drown in the roughness the
// contacts give J. The two alternate three times, because the accelerometer's x and y also
// read the trunk's tilt, which the trunk's centre of mass moves through the servos'
// compliance: the first bias update takes that tilt for a bias, and the rounds hand it back.
// That is the single fit (CalibrationOptions::staged false). The default, staged fit (issue 56)
// takes each value from the windows and channels that tell it (window_parts.hpp classifies
// them): the latency with the MX-64 torque and the friction on the arms' channels of the arms'
// windows, then the biases, the MX-106 torque and the trunk (fit_staged in
// calibration/src/fit_engine.hpp); logs without arm windows get the single fit.
// Uncertainty: the fit is repeated K times, each without one of
// K interleaved subsets of the windows, started from the full fit (a delete-a-group jackknife:
// sigma = sqrt((K-1)/K sum (theta_k - mean)^2), at least the subset fits' tolerance of 0.002
// parameter steps).
//
// Every evaluation is appended to a progress file; a run stopped (Ctrl-C) and started again
// with `resume` retraces the same deterministic path through the stored values, then goes on.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/sim_hal/log_replay.hpp"
#include "stride/sim_hal/world_file.hpp"

namespace stride::calibration {

/// A parameter the calibration can fit (`--fit NAME`): a world file's calibration quantity
/// (sim::calibration_quantities: name, unit, words, whole) and how it is fitted.
struct CalibrationParameter {
  std::string name;
  std::string unit;
  std::string what;
  double lower = 0.0, upper = 0.0;  ///< search bounds, inside the quantity's range
  double step = 0.0;                ///< the fit's initial step
  bool whole = false;               ///< whole numbers (the latency)
  /// Empty for a value the identification routine identifies; else why it does not, which
  /// stride calibrate prints as a warning when the value is fitted. The measure: the study of
  /// drawn robots (tests/bench/calibration_study.py, tests/bench/RESULTS.md), where a value
  /// without a warning lands within 20 % of its perturbation on at least 80 % of the robots.
  std::string caution = {};
  /// The same, only when the value named here is fitted too (the study fitted both).
  std::string caution_with = {}, caution_with_why = {};
};

/// Every fittable parameter, in the order they are reported.
const std::vector<CalibrationParameter>& calibration_parameters();
/// Parses a comma-separated list of names ("gyro_bias" and "accel_bias" stand for their three
/// axes, "all" for every parameter); the error names an unknown name and lists the known ones.
Status parse_fit_names(const std::string& list, std::vector<std::string>& out);
/// One warning line per value of `fit` the routine does not identify (CalibrationParameter::
/// caution, or caution_with when that value is in `fit` too), in table order.
std::vector<std::string> fit_warnings(const std::vector<std::string>& fit);
/// "(warned)", "(warned with NAME)" or "": how --help marks `p`.
std::string warning_mark(const CalibrationParameter& p);
double calibration_value(const sim::WorldFile& world, const std::string& name);
void set_calibration_value(sim::WorldFile& world, const std::string& name, double value);

struct CalibrationOptions {
  std::vector<std::string> fit;  ///< parameter names (parse_fit_names)
  sim::ReplayOptions replay;     ///< window length, threads (keep_traces unused)
  int max_evaluations = 250;     ///< per fit of the continuous parameters
  int subsets = 3;               ///< K for the uncertainty (0: none)
  /// The staged fit (window_parts.hpp, fit_staged): each value on the windows and channels
  /// that tell it best, from several starts; false: every value on every window at once.
  bool staged = true;
  std::filesystem::path progress_file;  ///< evaluations, one JSON line each ("" none)
  bool resume = false;                  ///< read progress_file's evaluations first
  const std::atomic<bool>* stop = nullptr;
  /// Called after each evaluation: the fit's name ("full", "subset 1", ...), the evaluation
  /// count, this J and the best J of this fit.
  std::function<void(const std::string&, int, double, double)> on_evaluation;
};

struct FittedValue {
  std::string name;
  double start = 0.0;
  double value = 0.0;
  double uncertainty = 0.0;  ///< jackknife standard error (0 without subsets)
  std::vector<double> subset_values;
};

struct CalibrationResult {
  sim::WorldFile world;  ///< the start world with the fitted values, "calibration" filled in
  std::vector<FittedValue> values;
  double nominal_objective = 0.0;  ///< J of the base world with nothing calibrated
  double start_objective = 0.0, objective = 0.0;
  sim::ReplayErrors start_errors, errors;  ///< RMS errors over the windows of the first log
  int evaluations = 0;                     ///< computed in this run (stored ones not counted)
  int stored_evaluations = 0;              ///< taken from the progress file (--resume)
};

/// Fits `options.fit` of `start` to `logs` (each checked by check_replayable and check_window)
/// replayed in `base` (the world options the replays run in; `start` is applied on top).
/// Errors: an interrupted fit ("interrupted"), a progress file that cannot be read or written,
/// a world that cannot be built.
Status calibrate(const std::vector<const fw::FlightLog*>& logs, const sim::WorldOptions& base,
                 const sim::WorldFile& start, const CalibrationOptions& options,
                 CalibrationResult& out);

/// The supply voltage the logs measured: the median of the CM730's readings over every log
/// [V]; false if no log has a reading.
bool logged_supply_voltage(const std::vector<const fw::FlightLog*>& logs, double& out);

/// The trunk mass scale that gives the simulated robot (`world`'s model) the weighed total
/// mass `robot_mass_kg`: the difference is put in the trunk (battery, cables). The error names
/// --robot-mass and the range it allows.
Status trunk_scale_for_mass(const sim::WorldOptions& world, double robot_mass_kg, double& out);

/// J of one replay result (the objective above).
double calibration_objective(const sim::ReplayResult& result);

}  // namespace stride::calibration
