// stride calibrate's shared fit parts (fit_engine.hpp): the objective over a selection of
// windows and channels, the evaluator (replays, cache, progress file) and the fit steps.
#include "fit_engine.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <nlohmann/json.hpp>

#include "stride/core/json_file.hpp"

namespace stride::calibration::detail {

using sim::ReplayErrors;
using sim::ReplayOptions;
using sim::ReplayResult;
using sim::ReplayWindow;
using sim::RobotCalibration;
using sim::WorldFile;
using sim::WorldOptions;

namespace {

double squared(double v, double scale) {
  return std::isfinite(v) ? (v / scale) * (v / scale) : 0.0;
}

std::string hex(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", v);
  return text;
}

/// The bias stage's rounds, and the updates below which it stops [rad/s, m/s^2].
constexpr int kBiasRounds = 4;
constexpr double kGyroBiasSettled = 1e-4, kAccelBiasSettled = 1e-3;
/// The search along each gyro axis after them: steps and passes [rad/s].
constexpr double kGyroStaircaseStep = 0.003;
constexpr int kStaircasePasses = 3;
constexpr int kAlternations = 3;

}  // namespace

double window_objective(const ReplayErrors& e, bool failed, std::uint32_t servos) {
  if (failed || e.samples == 0) return kFailedWindow;
  if (servos != 0) {  // the mean over the chosen servos of each channel's squared RMS
    double position = 0.0, speed = 0.0, load = 0.0, n = 0.0;
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      if (((servos >> i) & 1U) == 0) continue;
      position += squared(e.position_rad[i], kPositionScale);
      speed += squared(e.speed_rad_s[i], kSpeedScale);
      load += squared(e.load[i], kLoadScale);
      n += 1.0;
    }
    return n > 0.0 ? (position + speed + load) / n : 0.0;
  }
  double j = squared(e.position_all_rad, kPositionScale) + squared(e.speed_all_rad_s, kSpeedScale) +
             squared(e.load_all, kLoadScale) + squared(e.roll_rad, kAttitudeScale) +
             squared(e.pitch_rad, kAttitudeScale);
  for (int k = 0; k < 3; ++k)
    j += squared(e.gyro_rad_s[k], kGyroScale) + squared(e.accel_mps2[k], kAccelScale);
  return j;
}

Evaluator::Evaluator(const std::vector<const fw::FlightLog*>& logs, const WorldOptions& base,
                     const CalibrationOptions& options)
    : logs_(logs), base_(base), options_(options) {
  for (const fw::FlightLog* log : logs_)
    window_counts_.push_back(sim::count_windows(*log, options.replay.window_s));
}

Status Evaluator::open() {
  if (options_.progress_file.empty()) return Status::ok();
  if (options_.resume) {
    std::vector<nlohmann::json> lines;  // a line cut by a kill is skipped
    if (Status s = core::read_json_lines(options_.progress_file, lines); !s)
      return Status::error("--resume: " + s.message());
    for (const nlohmann::json& j : lines) {
      if (!j.contains("key") || !j["key"].is_string() || !j.contains("J") || !j["J"].is_string())
        continue;
      cache_[j["key"].get<std::string>()] = std::strtod(j["J"].get<std::string>().c_str(), nullptr);
      from_file_.insert(j["key"].get<std::string>());
    }
  }
  progress_.open(options_.progress_file, options_.resume ? std::ios::app : std::ios::trunc);
  if (!progress_)
    return Status::error("cannot write the progress file " + options_.progress_file.string());
  return Status::ok();
}

Status Evaluator::evaluate(const WorldFile& world, const WindowSelection& selection, double& j,
                           ReplayErrors* errors, ImuResidual* residual) {
  std::string key = std::to_string(selection.left_out);
  if (!selection.name.empty()) key += "/" + selection.name;
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
    for (std::size_t k = 0; k < window_counts_[l]; ++k, ++global) {
      const bool left_out = selection.left_out >= 0 &&
                            static_cast<int>(global % static_cast<std::size_t>(options_.subsets)) ==
                                selection.left_out;
      const bool unused =
          !selection.use.empty() && (global >= selection.use.size() || selection.use[global] == 0);
      if (!left_out && !unused) replay.only_windows.push_back(k);
    }
    if (replay.only_windows.empty()) continue;
    ReplayResult result;
    if (Status s = replay_flight_log(*logs_[l], w, replay, result); !s) return s;
    for (const ReplayWindow& win : result.windows) {
      const double n = static_cast<double>(std::max<std::size_t>(win.ticks, 1));
      sum += n * window_objective(win.errors, !win.failure.empty(), selection.servos);
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

const CalibrationParameter& parameter(const std::string& name) {
  for (const CalibrationParameter& p : calibration_parameters())
    if (p.name == name) return p;
  return calibration_parameters().front();  // names are checked by parse_fit_names
}

bool closed_form_bias(const std::string& name) {
  return name.rfind("gyro_bias_", 0) == 0 || name.rfind("accel_bias_", 0) == 0;
}

Status choose_latency(Evaluator& evaluator, const WindowSelection& selection, WorldFile& world,
                      double& j) {
  WorldFile best_world = world;
  if (Status s = evaluator.evaluate(world, selection, j); !s) return s;
  for (int l = 0; l <= RobotCalibration::kMaxLatencyTicks; ++l) {
    if (l == world.robot.latency_ticks) continue;
    WorldFile candidate = world;
    candidate.robot.latency_ticks = l;
    double jl = 0.0;
    if (Status s = evaluator.evaluate(candidate, selection, jl); !s) return s;
    if (jl < j) {
      j = jl;
      best_world = candidate;
    }
  }
  world = best_world;
  return Status::ok();
}

namespace {

struct FitContext {
  Evaluator* evaluator = nullptr;
  WorldFile world;                 ///< the whole-number parameters fixed, the others set by x
  std::vector<std::string> names;  ///< the continuous parameters
  std::vector<double> origin, step;
  const WindowSelection* selection = nullptr;
  std::string label;
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
  if (Status s = c.evaluator->evaluate(c.at(x), *c.selection, j); !s) {
    c.status = s;
    nlopt_force_stop(c.opt);
    return kFailedWindow;
  }
  ++c.count;
  c.best = std::min(c.best, j);
  if (c.evaluator->options().on_evaluation)
    c.evaluator->options().on_evaluation(c.label, c.count, j, c.best);
  return j;
}

}  // namespace

Status fit_continuous(Evaluator& evaluator, const std::vector<std::string>& names,
                      const WindowSelection& selection, const std::string& label, WorldFile& world,
                      double& best, double first_step, double xtol) {
  FitContext c;
  c.evaluator = &evaluator;
  c.world = world;
  c.names = names;
  c.selection = &selection;
  c.label = label;
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
  if (n == 0) return evaluator.evaluate(world, selection, best);
  c.opt = nlopt_create(NLOPT_LN_BOBYQA, n);
  nlopt_set_lower_bounds(c.opt, lower.data());
  nlopt_set_upper_bounds(c.opt, upper.data());
  nlopt_set_min_objective(c.opt, fit_objective, &c);
  nlopt_set_xtol_abs1(c.opt, xtol);  // in parameter steps
  nlopt_set_maxeval(c.opt, evaluator.options().max_evaluations);
  std::vector<double> initial_step(n, first_step);
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
Status fit_biases(Evaluator& evaluator, const std::vector<std::string>& names,
                  const WindowSelection& selection, WorldFile& world) {
  for (int round = 0; round < kBiasRounds; ++round) {
    double j = 0.0;
    ImuResidual r;
    if (Status s = evaluator.evaluate(world, selection, j, nullptr, &r); !s) return s;
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
    if (Status s = evaluator.evaluate(world, selection, best); !s) return s;
    for (int pass = 0; pass < kStaircasePasses; ++pass) {
      const double at = calibration_value(world, name);
      double chosen = at;
      for (double k : {-2.0, -1.0, 1.0, 2.0}) {
        WorldFile candidate = world;
        set_calibration_value(candidate, name,
                              std::clamp(at + k * kGyroStaircaseStep, p.lower, p.upper));
        double j = 0.0;
        if (Status s = evaluator.evaluate(candidate, selection, j); !s) return s;
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

/// The whole fit on `selection`: the latency tried at every value
/// (if fitted), the IMU biases in closed form, the other continuous parameters, the latency
/// again around the result and the biases again.
Status fit_all(Evaluator& evaluator, const std::vector<std::string>& fit,
               const WindowSelection& selection, const std::string& label, WorldFile& world,
               double& best) {
  const bool latency = std::find(fit.begin(), fit.end(), "latency") != fit.end();
  std::vector<std::string> continuous;
  for (const std::string& name : fit)
    if (!parameter(name).whole && !closed_form_bias(name)) continuous.push_back(name);
  // A subset's fit starts at the full fit, whose optimum it is near: a smaller first step and a
  // finer tolerance, so that the spread of the subsets is resolved (kSubsetTolerance).
  const bool subset = selection.left_out >= 0;
  const double first_step = subset ? 0.25 : 1.0, xtol = subset ? kSubsetTolerance : 0.02;
  double j = 0.0;
  if (latency)
    if (Status s = choose_latency(evaluator, selection, world, j); !s) return s;
  for (int round = 0; round < kAlternations; ++round) {
    if (Status s = fit_biases(evaluator, fit, selection, world); !s) return s;
    if (Status s =
            fit_continuous(evaluator, continuous, selection, label, world, best, first_step, xtol);
        !s)
      return s;
  }
  if (latency) {
    const int before = world.robot.latency_ticks;
    if (Status s = choose_latency(evaluator, selection, world, j); !s) return s;
    if (world.robot.latency_ticks != before) {
      if (Status s = fit_continuous(evaluator, continuous, selection, label, world, best,
                                    first_step, xtol);
          !s)
        return s;
    }
  }
  if (Status s = fit_biases(evaluator, fit, selection, world); !s) return s;
  return evaluator.evaluate(world, selection, best);
}

}  // namespace stride::calibration::detail
