// The parts of stride calibrate's fit (calibration.hpp) that the single fit (calibration.cpp)
// and the staged fit (staged_fit.cpp) share: the replay objective over a selection of windows
// and channels, the evaluator with its cache and progress file, and the fit steps (the latency
// search, the IMU biases in closed form, BOBYQA over the continuous values). Internal to
// stride_calibration.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "stride/calibration/calibration.hpp"

namespace stride::calibration::detail {

/// The channels of the objective and their scales (about one sensor resolution: the encoder's
/// 0.088 deg, the speed register's unit times 2, the load register's 1 %, the attitude filter's
/// 0.3 deg, the gyro's 0.02 rad/s, the accelerometer's 0.1 m/s^2).
constexpr double kPositionScale = 0.0015, kSpeedScale = 0.02, kLoadScale = 0.01,
                 kAttitudeScale = 0.005, kGyroScale = 0.02, kAccelScale = 0.1;
constexpr double kFailedWindow = 1e4;  ///< J of a window whose simulation stopped
/// The subset fits' tolerance in parameter steps: the smallest uncertainty reported.
constexpr double kSubsetTolerance = 0.002;

/// Which windows and channels an evaluation counts.
struct WindowSelection {
  int left_out = -1;      ///< the jackknife subset left out (-1: none)
  std::vector<char> use;  ///< per window over every log in order (empty: every window)
  /// 0: every channel (calibration.hpp's J); else only the position, speed and load of these
  /// servos (hal::servo_index bits), no attitude or IMU.
  std::uint32_t servos = 0;
  std::string name;  ///< part of the cache key ("" for every window and channel)
};

/// J of one window (the objective of calibration.hpp, or the servos' channels only).
double window_objective(const sim::ReplayErrors& e, bool failed, std::uint32_t servos = 0);

/// The mean logged-minus-simulated IMU reading over a replay.
struct ImuResidual {
  Eigen::Vector3d gyro_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
};

/// Replays the logs for a world and keeps every evaluation (memory and progress file).
class Evaluator {
 public:
  Evaluator(const std::vector<const fw::FlightLog*>& logs, const sim::WorldOptions& base,
            const CalibrationOptions& options);
  Status open();
  /// J of `world` over `selection`; `errors`: the first log's RMS errors; `residual`: the IMU's
  /// mean logged-minus-simulated reading over every selected window that ran to its end (a
  /// window that falls is not a bias).
  Status evaluate(const sim::WorldFile& world, const WindowSelection& selection, double& j,
                  sim::ReplayErrors* errors = nullptr, ImuResidual* residual = nullptr);
  int computed() const { return computed_; }
  int stored() const { return stored_; }
  const CalibrationOptions& options() const { return options_; }

 private:
  const std::vector<const fw::FlightLog*>& logs_;
  const sim::WorldOptions& base_;
  const CalibrationOptions& options_;
  std::vector<std::size_t> window_counts_;
  std::map<std::string, double> cache_;
  std::set<std::string> from_file_;  ///< progress-file entries not used yet
  std::ofstream progress_;
  int computed_ = 0, stored_ = 0;
};

const CalibrationParameter& parameter(const std::string& name);
/// The IMU biases, fitted in closed form (fit_biases).
bool closed_form_bias(const std::string& name);

/// The latency tried at every whole value; `world` set to the best, `j` its J.
Status choose_latency(Evaluator& evaluator, const WindowSelection& selection, sim::WorldFile& world,
                      double& j);
/// The IMU biases in `names` (the others are skipped) in closed form, then the gyro's on J.
Status fit_biases(Evaluator& evaluator, const std::vector<std::string>& names,
                  const WindowSelection& selection, sim::WorldFile& world);
/// BOBYQA over the continuous `names` from their present values in `world`, set to the best
/// point; `first_step`: the initial step in parameter steps, `xtol` the tolerance.
Status fit_continuous(Evaluator& evaluator, const std::vector<std::string>& names,
                      const WindowSelection& selection, const std::string& label,
                      sim::WorldFile& world, double& best, double first_step = 1.0,
                      double xtol = 0.02);
/// The single fit over `selection`: the latency, the biases and the continuous values in turn.
Status fit_all(Evaluator& evaluator, const std::vector<std::string>& fit,
               const WindowSelection& selection, const std::string& label, sim::WorldFile& world,
               double& best);

/// The staged fit (staged_fit.cpp): the latency on every window, the IMU biases on the still
/// windows, the MX-64 torque and the friction on the arms' channels of the arms' windows, the
/// MX-106 torque, then the trunk, each from several starts; a last joint polish of everything.
/// `selection` restricts it further (a jackknife subset). Falls back to fit_all for logs
/// without still or arm windows.
Status fit_staged(Evaluator& evaluator, const std::vector<const fw::FlightLog*>& logs,
                  const std::vector<std::string>& fit, const WindowSelection& selection,
                  const std::string& label, sim::WorldFile& world, double& best);

}  // namespace stride::calibration::detail
