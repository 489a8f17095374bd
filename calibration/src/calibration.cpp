// stride calibrate's fit (calibration.hpp): the fit (staged or single, fit_engine.hpp) and its
// jackknife, the supply from the logs and the trunk mass from the weighed robot (the objective,
// the evaluator and the fit steps: fit_engine.cpp; the staged fit: staged_fit.cpp; the
// parameters themselves: calibration_parameters.cpp).
#include "stride/calibration/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "fit_engine.hpp"

namespace stride::calibration {

using sim::ReplayResult;
using sim::ReplayWindow;
using sim::RobotModel;
using sim::WorldFile;
using sim::WorldOptions;

double calibration_objective(const ReplayResult& r) {
  double sum = 0.0, ticks = 0.0;
  for (const ReplayWindow& w : r.windows) {
    const double n = static_cast<double>(std::max<std::size_t>(w.ticks, 1));
    sum += n * detail::window_objective(w.errors, !w.failure.empty());
    ticks += n;
  }
  return ticks > 0.0 ? sum / ticks : detail::kFailedWindow;
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

Status calibrate(const std::vector<const fw::FlightLog*>& logs, const WorldOptions& base,
                 const WorldFile& start, const CalibrationOptions& options,
                 CalibrationResult& out) {
  out = {};
  if (options.fit.empty()) return Status::error("--fit: name at least one parameter");
  using detail::WindowSelection;
  detail::Evaluator evaluator(logs, base, options);
  if (Status s = evaluator.open(); !s) return s;
  if (Status s =
          evaluator.evaluate(start, WindowSelection{}, out.start_objective, &out.start_errors);
      !s)
    return s;
  WorldFile nominal;  // the base world with nothing calibrated
  nominal.base = start.base;
  if (Status s = evaluator.evaluate(nominal, WindowSelection{}, out.nominal_objective); !s)
    return s;
  WorldFile world = start;
  double best = 0.0;
  const auto fit = [&](const WindowSelection& selection, const std::string& label, WorldFile& w,
                       double& j) {
    return options.staged ? detail::fit_staged(evaluator, logs, options.fit, selection, label, w, j)
                          : detail::fit_all(evaluator, options.fit, selection, label, w, j);
  };
  if (Status s = fit(WindowSelection{}, "full", world, best); !s) return s;
  out.objective = best;
  for (const std::string& name : options.fit)
    out.values.push_back(
        {name, calibration_value(start, name), calibration_value(world, name), 0.0, {}});
  // Jackknife: K fits, each without one subset, started from the full fit.
  for (int k = 0; k < options.subsets && options.subsets >= 2; ++k) {
    WorldFile sub = world;
    double j = 0.0;
    if (Status s = fit(WindowSelection{k, {}, 0, {}}, "subset " + std::to_string(k + 1), sub, j);
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
    const CalibrationParameter& p = detail::parameter(v.name);
    v.uncertainty = std::sqrt((k - 1.0) / k * sq);
    if (!p.whole) v.uncertainty = std::max(v.uncertainty, detail::kSubsetTolerance * p.step);
  }
  double check = 0.0;
  if (Status s = evaluator.evaluate(world, WindowSelection{}, check, &out.errors); !s) return s;
  out.evaluations = evaluator.computed();
  out.stored_evaluations = evaluator.stored();
  nlohmann::json fitted = nlohmann::json::object();
  for (const FittedValue& v : out.values)
    fitted[v.name] = {{"value", v.value},
                      {"start", v.start},
                      {"uncertainty", v.uncertainty},
                      {"unit", detail::parameter(v.name).unit}};
  world.calibration = {{"fitted", fitted},
                       {"objective_nominal", out.nominal_objective},
                       {"objective_start", out.start_objective},
                       {"objective", out.objective},
                       {"window_s", options.replay.window_s},
                       {"subsets", options.subsets},
                       {"staged", options.staged}};
  out.world = world;
  return Status::ok();
}

}  // namespace stride::calibration
