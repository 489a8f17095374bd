// stride calibrate's fit (calibration.hpp): the objective over the replayed windows, the IMU
// biases in closed form, NLopt's BOBYQA, the latency search, the jackknife and the progress file
// (the parameters themselves: calibration_parameters.cpp).
#include "stride/calibration/calibration.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "stride/core/json_file.hpp"

namespace stride::calibration {

using sim::count_windows;
using sim::ReplayErrors;
using sim::ReplayOptions;
using sim::ReplayResult;
using sim::ReplayWindow;
using sim::RobotCalibration;
using sim::RobotModel;
using sim::WorldFile;
using sim::WorldOptions;

namespace {

/// The channels of the objective and their scales (about one sensor resolution: the encoder's
/// 0.088 deg, the speed register's unit times 2, the load register's 1 %, the attitude filter's
/// 0.3 deg, the gyro's 0.02 rad/s, the accelerometer's 0.1 m/s^2).
constexpr double kPositionScale = 0.0015, kSpeedScale = 0.02, kLoadScale = 0.01,
                 kAttitudeScale = 0.005, kGyroScale = 0.02, kAccelScale = 0.1;
constexpr double kFailedWindow = 1e4;  ///< J of a window whose simulation stopped
/// The subset fits' tolerance in parameter steps: the smallest uncertainty reported.
constexpr double kSubsetTolerance = 0.002;

double window_objective(const ReplayErrors& e, bool failed) {
  if (failed || e.samples == 0) return kFailedWindow;
  const auto sq = [](double v, double scale) {
    return std::isfinite(v) ? (v / scale) * (v / scale) : 0.0;
  };
  double j = sq(e.position_all_rad, kPositionScale) + sq(e.speed_all_rad_s, kSpeedScale) +
             sq(e.load_all, kLoadScale) + sq(e.roll_rad, kAttitudeScale) +
             sq(e.pitch_rad, kAttitudeScale);
  for (int k = 0; k < 3; ++k)
    j += sq(e.gyro_rad_s[k], kGyroScale) + sq(e.accel_mps2[k], kAccelScale);
  return j;
}

std::string hex(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", v);
  return text;
}

}  // namespace

double calibration_objective(const ReplayResult& r) {
  double sum = 0.0, ticks = 0.0;
  for (const ReplayWindow& w : r.windows) {
    const double n = static_cast<double>(std::max<std::size_t>(w.ticks, 1));
    sum += n * window_objective(w.errors, !w.failure.empty());
    ticks += n;
  }
  return ticks > 0.0 ? sum / ticks : kFailedWindow;
}

bool logged_supply_voltage(const std::vector<const fw::FlightLog*>& logs, double& out) {
  std::vector<double> volts;
  for (const fw::FlightLog* log : logs)
    for (const fw::FlightLogTick& t : log->ticks)
      if (t.sensors.cm730.health == hal::DeviceHealth::kOk && t.sensors.cm730.voltage_v > 0.0)
        volts.push_back(t.sensors.cm730.voltage_v);
  if (volts.empty()) return false;
  const auto middle = volts.begin() + static_cast<std::ptrdiff_t>(volts.size() / 2);
  std::nth_element(volts.begin(), middle, volts.end());
  out = *middle;
  return true;
}

Status trunk_scale_for_mass(const WorldOptions& world, double robot_mass_kg, double& out) {
  RobotModel loaded;
  const RobotModel* model = world.model.get();
  if (model == nullptr) {
    if (Status s = RobotModel::load_file(world.urdf, loaded); !s) return s;
    model = &loaded;
  }
  const double trunk = model->links().front().mass;
  const double total = model->total_mass();
  out = 1.0 + (robot_mass_kg - total) / trunk;
  const sim::CalibrationQuantity& range = *sim::find_calibration_quantity("trunk_mass");
  const double lo = total + (range.min - 1.0) * trunk, hi = total + (range.max - 1.0) * trunk;
  if (!std::isfinite(robot_mass_kg) || out < range.min || out > range.max) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "--robot-mass: %.3g kg is too far from the model's %.3f kg (allowed %.2f to "
                  "%.2f kg: the difference goes into the %.3f kg trunk)",
                  robot_mass_kg, total, lo, hi, trunk);
    return Status::error(text);
  }
  return Status::ok();
}

namespace {

/// The mean logged-minus-simulated IMU reading over a replay (Evaluator::evaluate).
struct ImuResidual {
  Eigen::Vector3d gyro_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
};

/// The bias stage's rounds, and the updates below which it stops [rad/s, m/s^2].
constexpr int kBiasRounds = 4;
constexpr double kGyroBiasSettled = 1e-4, kAccelBiasSettled = 1e-3;
/// The search along each gyro axis after them: steps and passes [rad/s].
constexpr double kGyroStaircaseStep = 0.003;
constexpr int kStaircasePasses = 3;

/// The biases fitted in closed form (fit_biases): the gyro's three and the accelerometer's z.
/// The accelerometer's x and y also read the trunk's tilt (g sin of it), which the trunk's
/// centre of mass moves through the servos' compliance: they stay in the joint fit.
bool closed_form_bias(const std::string& name) {
  return name.rfind("gyro_bias_", 0) == 0 || name.rfind("accel_bias_", 0) == 0;
}
constexpr int kAlternations = 3;

const CalibrationParameter& parameter(const std::string& name) {
  for (const CalibrationParameter& p : calibration_parameters())
    if (p.name == name) return p;
  return calibration_parameters().front();  // names are checked by parse_fit_names
}

/// Replays the logs for a world and keeps every evaluation (memory and progress file).
class Evaluator {
 public:
  Evaluator(const std::vector<const fw::FlightLog*>& logs, const WorldOptions& base,
            const CalibrationOptions& options)
      : logs_(logs), base_(base), options_(options) {
    for (const fw::FlightLog* log : logs_)
      window_counts_.push_back(count_windows(*log, options.replay.window_s));
  }

  Status open() {
    if (options_.progress_file.empty()) return Status::ok();
    if (options_.resume) {
      std::vector<nlohmann::json> lines;  // a line cut by a kill is skipped
      if (Status s = core::read_json_lines(options_.progress_file, lines); !s)
        return Status::error("--resume: " + s.message());
      for (const nlohmann::json& j : lines) {
        if (!j.contains("key") || !j["key"].is_string() || !j.contains("J") || !j["J"].is_string())
          continue;
        cache_[j["key"].get<std::string>()] =
            std::strtod(j["J"].get<std::string>().c_str(), nullptr);
        from_file_.insert(j["key"].get<std::string>());
      }
    }
    progress_.open(options_.progress_file, options_.resume ? std::ios::app : std::ios::trunc);
    if (!progress_)
      return Status::error("cannot write the progress file " + options_.progress_file.string());
    return Status::ok();
  }

  /// J of `world` over the windows not in subset `left_out` of `subsets` (-1: all windows);
  /// `errors`: the first log's RMS errors; `residual`: the IMU's mean logged-minus-simulated
  /// reading over every window that ran to its end (a window that falls is not a bias).
  Status evaluate(const WorldFile& world, int left_out, double& j, ReplayErrors* errors = nullptr,
                  ImuResidual* residual = nullptr) {
    std::string key = std::to_string(left_out);
    for (const CalibrationParameter& p : calibration_parameters())
      key += " " + hex(calibration_value(world, p.name));
    if (errors == nullptr && residual == nullptr) {
      if (auto it = cache_.find(key); it != cache_.end()) {
        j = it->second;
        if (from_file_.erase(key) > 0) ++stored_;
        return Status::ok();
      }
    }
    if (options_.stop && options_.stop->load()) return Status::error("interrupted");
    WorldOptions w = base_;
    world.apply_calibration(w);
    double sum = 0.0, ticks = 0.0;
    std::size_t global = 0;
    ReplayErrors all{};
    ImuResidual mean;
    double imu_samples = 0.0;
    for (std::size_t l = 0; l < logs_.size(); ++l) {
      ReplayOptions replay = options_.replay;
      replay.keep_traces = false;
      replay.only_windows.clear();
      for (std::size_t k = 0; k < window_counts_[l]; ++k, ++global)
        if (left_out < 0 ||
            static_cast<int>(global % static_cast<std::size_t>(options_.subsets)) != left_out)
          replay.only_windows.push_back(k);
      if (replay.only_windows.empty()) continue;
      ReplayResult result;
      if (Status s = replay_flight_log(*logs_[l], w, replay, result); !s) return s;
      for (const ReplayWindow& win : result.windows) {
        const double n = static_cast<double>(std::max<std::size_t>(win.ticks, 1));
        sum += n * window_objective(win.errors, !win.failure.empty());
        ticks += n;
        const auto m = static_cast<double>(win.errors.mean_samples);
        if (!win.failure.empty() || m == 0.0) continue;
        mean.gyro_rad_s += m * win.errors.gyro_mean_rad_s;
        mean.accel_mps2 += m * win.errors.accel_mean_mps2;
        imu_samples += m;
      }
      if (l == 0) all = result.overall;  // the first log's errors, reported
    }
    j = ticks > 0.0 ? sum / ticks : kFailedWindow;
    if (errors) *errors = all;
    if (residual) {
      *residual = {};
      if (imu_samples > 0.0) {
        residual->gyro_rad_s = mean.gyro_rad_s / imu_samples;
        residual->accel_mps2 = mean.accel_mps2 / imu_samples;
      }
    }
    cache_[key] = j;
    ++computed_;
    if (progress_.is_open()) {
      progress_ << nlohmann::json({{"key", key}, {"J", hex(j)}}).dump() << "\n";
      progress_.flush();
      if (!progress_) return Status::error("cannot write the progress file");
    }
    return Status::ok();
  }

  int computed() const { return computed_; }
  int stored() const { return stored_; }

 private:
  const std::vector<const fw::FlightLog*>& logs_;
  const WorldOptions& base_;
  const CalibrationOptions& options_;
  std::vector<std::size_t> window_counts_;
  std::map<std::string, double> cache_;
  std::set<std::string> from_file_;  ///< progress-file entries not used yet
  std::ofstream progress_;
  int computed_ = 0, stored_ = 0;
};

struct FitContext {
  Evaluator* evaluator = nullptr;
  WorldFile world;                 ///< the whole-number parameters fixed, the others set by x
  std::vector<std::string> names;  ///< the continuous parameters
  std::vector<double> origin, step;
  int left_out = -1;
  std::string label;
  const CalibrationOptions* options = nullptr;
  Status status = Status::ok();
  int count = 0;
  double best = std::numeric_limits<double>::infinity();
  nlopt_opt opt = nullptr;

  WorldFile at(const double* x) const {
    WorldFile w = world;
    for (std::size_t i = 0; i < names.size(); ++i)
      set_calibration_value(w, names[i], origin[i] + step[i] * x[i]);
    return w;
  }
};

double fit_objective(unsigned /*n*/, const double* x, double* /*grad*/, void* data) {
  auto& c = *static_cast<FitContext*>(data);
  double j = kFailedWindow;
  if (Status s = c.evaluator->evaluate(c.at(x), c.left_out, j); !s) {
    c.status = s;
    nlopt_force_stop(c.opt);
    return kFailedWindow;
  }
  ++c.count;
  c.best = std::min(c.best, j);
  if (c.options->on_evaluation) c.options->on_evaluation(c.label, c.count, j, c.best);
  return j;
}

/// BOBYQA over the continuous parameters of `world` from their present values; `world` is set
/// to the best point.
Status fit_continuous(Evaluator& evaluator, const std::vector<std::string>& names, int left_out,
                      const std::string& label, const CalibrationOptions& options, WorldFile& world,
                      double& best) {
  FitContext c;
  c.evaluator = &evaluator;
  c.world = world;
  c.names = names;
  c.left_out = left_out;
  c.label = label;
  c.options = &options;
  const auto n = static_cast<unsigned>(names.size());
  std::vector<double> x(n, 0.0), lower(n), upper(n);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const CalibrationParameter& p = parameter(names[i]);
    c.origin.push_back(calibration_value(world, names[i]));
    c.step.push_back(p.step);
    lower[i] = (p.lower - c.origin[i]) / p.step;
    upper[i] = (p.upper - c.origin[i]) / p.step;
    x[i] = std::clamp(0.0, lower[i], upper[i]);
  }
  if (n == 0) return evaluator.evaluate(world, left_out, best);
  c.opt = nlopt_create(NLOPT_LN_BOBYQA, n);
  nlopt_set_lower_bounds(c.opt, lower.data());
  nlopt_set_upper_bounds(c.opt, upper.data());
  nlopt_set_min_objective(c.opt, fit_objective, &c);
  // A subset's fit starts at the full fit, whose optimum it is near: a smaller first step and a
  // finer tolerance, so that the spread of the subsets is resolved (kSubsetTolerance).
  const bool subset = left_out >= 0;
  nlopt_set_xtol_abs1(c.opt, subset ? kSubsetTolerance : 0.02);  // in parameter steps
  nlopt_set_maxeval(c.opt, options.max_evaluations);
  std::vector<double> initial_step(n, subset ? 0.25 : 1.0);
  nlopt_set_initial_step(c.opt, initial_step.data());
  double value = 0.0;
  const nlopt_result r = nlopt_optimize(c.opt, x.data(), &value);
  nlopt_destroy(c.opt);
  if (!c.status) return c.status;
  if (r < 0 && r != NLOPT_ROUNDOFF_LIMITED)
    return Status::error("the fit failed (NLopt code " + std::to_string(static_cast<int>(r)) + ")");
  world = c.at(x.data());
  best = value;
  return Status::ok();
}

/// The IMU biases in `names` (the others are skipped) fitted in closed form: a constant bias
/// the world lacks is the mean of the logged minus the simulated reading, which is what the
/// objective's IMU terms are least at (the replay is open loop: the commands are the logged
/// ones, so the bias moves nothing else). A few rounds, because the accelerometer's mean also
/// carries the attitude the simulated trunk settles at. A derivative-free fit over every value
/// at once leaves them near their start: their few units of J drown in the contact's roughness.
Status fit_biases(Evaluator& evaluator, const std::vector<std::string>& names, int left_out,
                  WorldFile& world) {
  for (int round = 0; round < kBiasRounds; ++round) {
    double j = 0.0;
    ImuResidual r;
    if (Status s = evaluator.evaluate(world, left_out, j, nullptr, &r); !s) return s;
    bool settled = true;
    for (const std::string& name : names) {
      if (!closed_form_bias(name)) continue;
      const int axis = name.back() - 'x';
      const bool gyro = name.rfind("gyro_bias_", 0) == 0;
      const double update = gyro ? r.gyro_rad_s[axis] : r.accel_mps2[axis];
      if (!std::isfinite(update)) continue;
      const CalibrationParameter& p = parameter(name);
      set_calibration_value(world, name,
                            std::clamp(calibration_value(world, name) + update, p.lower, p.upper));
      settled = settled && std::abs(update) < (gyro ? kGyroBiasSettled : kAccelBiasSettled);
    }
    if (settled) break;
  }
  // The CM730's registers read the gyro in steps of 0.061 rad/s, several times the bias, and
  // the chips' noise hardly dithers them: the mean above is a staircase's, and the replay error
  // tells the bias only where the motion carries a reading across a step. A search along each
  // gyro axis on the objective itself settles what the mean could not.
  for (const std::string& name : names) {
    if (name.rfind("gyro_bias_", 0) != 0) continue;
    const CalibrationParameter& p = parameter(name);
    double best = 0.0;
    if (Status s = evaluator.evaluate(world, left_out, best); !s) return s;
    for (int pass = 0; pass < kStaircasePasses; ++pass) {
      const double at = calibration_value(world, name);
      double chosen = at;
      for (double k : {-2.0, -1.0, 1.0, 2.0}) {
        WorldFile candidate = world;
        set_calibration_value(candidate, name,
                              std::clamp(at + k * kGyroStaircaseStep, p.lower, p.upper));
        double j = 0.0;
        if (Status s = evaluator.evaluate(candidate, left_out, j); !s) return s;
        if (j < best) {
          best = j;
          chosen = calibration_value(candidate, name);
        }
      }
      if (chosen == at) break;
      set_calibration_value(world, name, chosen);
    }
  }
  return Status::ok();
}

/// The whole fit on the windows without subset `left_out`: the latency tried at every value
/// (if fitted), the IMU biases in closed form, the other continuous parameters, the latency
/// again around the result and the biases again.
Status fit_all(Evaluator& evaluator, const std::vector<std::string>& fit, int left_out,
               const std::string& label, const CalibrationOptions& options, WorldFile& world,
               double& best) {
  const bool latency = std::find(fit.begin(), fit.end(), "latency") != fit.end();
  std::vector<std::string> continuous;
  for (const std::string& name : fit)
    if (!parameter(name).whole && !closed_form_bias(name)) continuous.push_back(name);
  const auto choose_latency = [&](WorldFile& w, double& j) -> Status {
    WorldFile best_world = w;
    if (Status s = evaluator.evaluate(w, left_out, j); !s) return s;
    for (int l = 0; l <= RobotCalibration::kMaxLatencyTicks; ++l) {
      if (l == w.robot.latency_ticks) continue;
      WorldFile candidate = w;
      candidate.robot.latency_ticks = l;
      double jl = 0.0;
      if (Status s = evaluator.evaluate(candidate, left_out, jl); !s) return s;
      if (jl < j) {
        j = jl;
        best_world = candidate;
      }
    }
    w = best_world;
    return Status::ok();
  };
  double j = 0.0;
  if (latency)
    if (Status s = choose_latency(world, j); !s) return s;
  for (int round = 0; round < kAlternations; ++round) {
    if (Status s = fit_biases(evaluator, fit, left_out, world); !s) return s;
    if (Status s = fit_continuous(evaluator, continuous, left_out, label, options, world, best); !s)
      return s;
  }
  if (latency) {
    const int before = world.robot.latency_ticks;
    if (Status s = choose_latency(world, j); !s) return s;
    if (world.robot.latency_ticks != before) {
      if (Status s = fit_continuous(evaluator, continuous, left_out, label, options, world, best);
          !s)
        return s;
    }
  }
  if (Status s = fit_biases(evaluator, fit, left_out, world); !s) return s;
  return evaluator.evaluate(world, left_out, best);
}

}  // namespace

Status calibrate(const std::vector<const fw::FlightLog*>& logs, const WorldOptions& base,
                 const WorldFile& start, const CalibrationOptions& options,
                 CalibrationResult& out) {
  out = {};
  if (options.fit.empty()) return Status::error("--fit: name at least one parameter");
  Evaluator evaluator(logs, base, options);
  if (Status s = evaluator.open(); !s) return s;
  if (Status s = evaluator.evaluate(start, -1, out.start_objective, &out.start_errors); !s)
    return s;
  WorldFile nominal;  // the base world with nothing calibrated
  nominal.base = start.base;
  if (Status s = evaluator.evaluate(nominal, -1, out.nominal_objective); !s) return s;
  WorldFile world = start;
  double best = 0.0;
  if (Status s = fit_all(evaluator, options.fit, -1, "full", options, world, best); !s) return s;
  out.objective = best;
  for (const std::string& name : options.fit)
    out.values.push_back(
        {name, calibration_value(start, name), calibration_value(world, name), 0.0, {}});
  // Jackknife: K fits, each without one subset, started from the full fit.
  for (int k = 0; k < options.subsets && options.subsets >= 2; ++k) {
    WorldFile sub = world;
    double j = 0.0;
    if (Status s =
            fit_all(evaluator, options.fit, k, "subset " + std::to_string(k + 1), options, sub, j);
        !s)
      return s;
    for (FittedValue& v : out.values) v.subset_values.push_back(calibration_value(sub, v.name));
  }
  for (FittedValue& v : out.values) {
    const auto k = static_cast<double>(v.subset_values.size());
    if (k < 2) continue;
    double mean = 0.0, sq = 0.0;
    for (double x : v.subset_values) mean += x / k;
    for (double x : v.subset_values) sq += (x - mean) * (x - mean);
    // Not below what the subset fits resolve (a spread under their tolerance reads as 0).
    const CalibrationParameter& p = parameter(v.name);
    v.uncertainty = std::sqrt((k - 1.0) / k * sq);
    if (!p.whole) v.uncertainty = std::max(v.uncertainty, kSubsetTolerance * p.step);
  }
  double check = 0.0;
  if (Status s = evaluator.evaluate(world, -1, check, &out.errors); !s) return s;
  out.evaluations = evaluator.computed();
  out.stored_evaluations = evaluator.stored();
  nlohmann::json fitted = nlohmann::json::object();
  for (const FittedValue& v : out.values)
    fitted[v.name] = {{"value", v.value},
                      {"start", v.start},
                      {"uncertainty", v.uncertainty},
                      {"unit", parameter(v.name).unit}};
  world.calibration = {{"fitted", fitted},
                       {"objective_nominal", out.nominal_objective},
                       {"objective_start", out.start_objective},
                       {"objective", out.objective},
                       {"window_s", options.replay.window_s},
                       {"subsets", options.subsets}};
  out.world = world;
  return Status::ok();
}

}  // namespace stride::calibration
