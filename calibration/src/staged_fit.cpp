// The staged fit of stride calibrate (fit_engine.hpp, issue 56 point 2). Each value is fitted
// on the windows and channels that tell it best, in the order in which they depend on each
// other (window_parts.hpp names the windows):
//   1. the latency with the MX-64 torque and the friction, on the arms' windows, counting only
//      the arms' position, speed and load: the arms hold the loads the URDF gives, free of
//      contacts, with quick set-point steps (identify_arms), so the trunk's unknowns do not leak
//      in. Each latency gets its own fit of the two, because a weaker arm looks like a tick more
//      of delay; the best latency's is refined from several starts;
//   2. the IMU biases in closed form over the still, legs' and steps' windows (calibration.hpp says
//      why not the still ones alone: the gyro's register steps need the motion to carry a
//      reading across them; the walk's windows diverge);
//   3. the MX-106 torque and the trunk (centre of mass, and the mass or supply if asked)
//      together, on the same windows, the friction and the MX-64 held, then the biases again;
//      twice, because the accelerometer reads the trunk's tilt. Kept only if J over every
//      window (the walk's too) is not worse than without them.
// Each continuous stage starts BOBYQA from the present values and from two points kStartSteps
// fit steps either side along every value at once, and keeps the best: J of the servo and trunk
// values has shallow valleys the contacts make rough, where one start stops early. A log
// without arm windows (recorded before identify_arms) gets the single fit.
#include <algorithm>
#include <cmath>

#include "fit_engine.hpp"
#include "stride/calibration/window_parts.hpp"

namespace stride::calibration::detail {

using sim::WorldFile;

namespace {

constexpr double kStartSteps = 1.5;  ///< the other starts, in fit steps from the present values
constexpr int kTrunkRounds = 2;      ///< MX-106 and trunk, then IMU biases, alternated

bool contains(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

/// The names of `wanted` that `fit` has, in `wanted`'s order.
std::vector<std::string> chosen(const std::vector<std::string>& fit,
                                const std::vector<std::string>& wanted) {
  std::vector<std::string> out;
  for (const std::string& name : wanted)
    if (contains(fit, name)) out.push_back(name);
  return out;
}

/// BOBYQA from the present values and from kStartSteps either side; `world` set to the best.
Status fit_from_starts(Evaluator& evaluator, const std::vector<std::string>& names,
                       const WindowSelection& selection, const std::string& label, WorldFile& world,
                       double& best) {
  if (names.empty()) return Status::ok();
  const bool subset = selection.left_out >= 0;  // near the full fit's optimum: one start
  const double xtol = subset ? kSubsetTolerance : 0.02;
  WorldFile best_world = world;
  best = kFailedWindow * 10.0;
  for (double offset :
       subset ? std::vector<double>{0.0} : std::vector<double>{0.0, -kStartSteps, kStartSteps}) {
    WorldFile start = world;
    for (const std::string& name : names) {
      const CalibrationParameter& p = parameter(name);
      set_calibration_value(
          start, name,
          std::clamp(calibration_value(world, name) + offset * p.step, p.lower, p.upper));
    }
    double j = 0.0;
    if (Status s =
            fit_continuous(evaluator, names, selection, label, start, j, subset ? 0.25 : 1.0, xtol);
        !s)
      return s;
    if (j < best) {
      best = j;
      best_world = start;
    }
  }
  world = best_world;
  return Status::ok();
}

/// `base` restricted to the windows whose part is one of `parts`; empty `use` if none is.
WindowSelection restrict(const WindowSelection& base, const std::vector<WindowPart>& windows,
                         std::initializer_list<WindowPart> parts, std::uint32_t servos,
                         const std::string& name) {
  WindowSelection s = base;
  s.use.assign(windows.size(), 0);
  bool any = false;
  for (std::size_t k = 0; k < windows.size(); ++k) {
    const bool wanted = std::find(parts.begin(), parts.end(), windows[k]) != parts.end();
    s.use[k] = static_cast<char>(wanted && (base.use.empty() || base.use[k] != 0));
    any = any || wanted;
  }
  if (!any) s.use.clear();
  s.servos = servos;
  s.name = name;
  return s;
}

bool has(const std::vector<WindowPart>& windows, WindowPart part) {
  return std::find(windows.begin(), windows.end(), part) != windows.end();
}

}  // namespace

Status fit_staged(Evaluator& evaluator, const std::vector<const fw::FlightLog*>& logs,
                  const std::vector<std::string>& fit, const WindowSelection& selection,
                  const std::string& label, WorldFile& world, double& best) {
  const double window_s = evaluator.options().replay.window_s;
  std::vector<WindowPart> windows;
  std::uint32_t arms = 0;
  for (const fw::FlightLog* log : logs) {
    const std::vector<WindowPart> parts = classify_windows(*log, window_s);
    windows.insert(windows.end(), parts.begin(), parts.end());
    arms |= arm_servo_mask(*log);
  }
  // Without arm windows the MX-64 and the latency have no clean windows: the single fit.
  if (!has(windows, WindowPart::kArms) || arms == 0)
    return fit_all(evaluator, fit, selection, label, world, best);

  const WindowSelection all = selection;
  const WindowSelection arm =
      restrict(selection, windows, {WindowPart::kArms}, arms, "arms/servos");
  // The trunk and the biases on the windows that stand or move the legs: not the walk (its
  // contacts diverge within a window) nor the arms (fitted, and a third of the cost). The steps
  // stay: left out, the MX-106 and the trunk's centre of mass were found on none and one of six
  // study robots, against two and three with them (tests/bench/RESULTS.md).
  const WindowSelection standing = restrict(
      selection, windows, {WindowPart::kStill, WindowPart::kLegs, WindowPart::kSteps}, 0, "stand");
  std::vector<std::string> biases;
  for (const std::string& name : fit)
    if (closed_form_bias(name)) biases.push_back(name);
  const std::vector<std::string> arm_values = chosen(fit, {"torque_mx64", "friction"});
  const std::vector<std::string> leg_values = chosen(fit, {"torque_mx106"});
  std::vector<std::string> trunk_values;  // every other continuous value
  for (const std::string& name : fit)
    if (!parameter(name).whole && !closed_form_bias(name) && !contains(arm_values, name) &&
        !contains(leg_values, name))
      trunk_values.push_back(name);

  // The latency and the arms' values together on the arms' channels: contact-free, with quick
  // set-point steps. A weaker or stiffer arm looks like a tick more or less of delay, so each
  // latency gets its own fit of the arms' values, and the best pair is refined from the starts.
  double j = 0.0;
  if (contains(fit, "latency")) {
    WorldFile best_world = world;
    double best_j = kFailedWindow * 10.0;
    for (int l = 0; l <= sim::RobotCalibration::kMaxLatencyTicks; ++l) {
      WorldFile candidate = world;
      candidate.robot.latency_ticks = l;
      if (Status s = fit_continuous(evaluator, arm_values, arm,
                                    label + ", latency " + std::to_string(l), candidate, j);
          !s)
        return s;
      if (j < best_j) {
        best_j = j;
        best_world = candidate;
      }
    }
    world = best_world;
  }
  if (Status s = fit_from_starts(evaluator, arm_values, arm, label + ", arms", world, j); !s)
    return s;
  if (Status s = fit_biases(evaluator, biases, standing, world); !s) return s;
  // The MX-106 and the trunk together: on the legs' windows the legs' deflection under the
  // trunk's weight and the trunk's lever trade, so one fitted before the other takes the
  // other's part. Biases in between, which read the trunk's tilt.
  std::vector<std::string> body_values = leg_values;
  body_values.insert(body_values.end(), trunk_values.begin(), trunk_values.end());
  const WorldFile before_body = world;
  for (int round = 0; round < kTrunkRounds; ++round) {
    if (Status s =
            fit_from_starts(evaluator, body_values, standing, label + ", legs and trunk", world, j);
        !s)
      return s;
    if (Status s = fit_biases(evaluator, biases, standing, world); !s) return s;
  }
  // The stages above never replay the walk: a body that fits the standing windows but makes a
  // walk window fall (J of a failed window is 1e4) is worse than none; keep the values before.
  if (Status s = evaluator.evaluate(world, all, best); !s) return s;
  double without = 0.0;
  if (Status s = evaluator.evaluate(before_body, all, without); !s) return s;
  if (without < best) {
    world = before_body;
    best = without;
  }
  return Status::ok();
}

}  // namespace stride::calibration::detail
