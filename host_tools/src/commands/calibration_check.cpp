// The check stride calibrate prints after a fit (calibration_check.hpp).
#include "calibration_check.hpp"

#include <cmath>
#include <cstdio>
#include <memory>

#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::tools {
namespace {

namespace sim = stride::sim;

constexpr double kGoalWalkS = 30.0;                      ///< the forward walk to 2.5 m [s]
constexpr double kSpeedFromS = 5.0, kSpeedToS = 20.0;    ///< the speed's span [s]
constexpr double kPushAtS = 8.0, kPushAfterS = 4.0;      ///< the push and the survival after [s]
constexpr double kPushMax = 4.0, kPushResolution = 0.1;  ///< the bisection [N s]
constexpr double kPi = 3.14159265358979323846;

/// One of the six walk directions: the command and the coordinate that measures progress.
struct Direction {
  const char* name;
  double vx, vy, vth;
};
constexpr std::array<Direction, 6> kDirections{{{"forward", 1, 0, 0},
                                                {"backward", -1, 0, 0},
                                                {"left", 0, 1, 0},
                                                {"right", 0, -1, 0},
                                                {"turn left", 0, 0, 1},
                                                {"turn right", 0, 0, -1}}};
constexpr std::array<const char*, 4> kPushNames{"forward", "backward", "left", "right"};
constexpr std::array<double, 4> kPushDirections{0.0, kPi, 0.5 * kPi, -0.5 * kPi};

double yaw_of(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d r = pose.rotation();
  return std::atan2(r(1, 0), r(0, 0));
}

/// The torso's position and unwrapped yaw at two moments of an episode.
struct Progress {
  Eigen::Vector3d from_position = Eigen::Vector3d::Zero(), to_position = Eigen::Vector3d::Zero();
  double from_yaw = 0.0, to_yaw = 0.0, yaw = 0.0, last_yaw = 0.0;
  bool started = false;
};

/// The default walk in `world` for `duration_s` with the command (vx, vy, vth); `progress`
/// (optional) follows the torso from kSpeedFromS to the end.
Status walk(const sim::WorldOptions& world, const Direction& d, double duration_s,
            sim::EpisodeResult& result, Progress* progress) {
  fw::FirmwareOptions firmware_options;  // the firmware's defaults
  std::unique_ptr<fw::Firmware> firmware;
  if (Status s = fw::Firmware::create(firmware_options, firmware); !s) return s;
  sim::WorldOptions options = world;
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> sim_world;
  if (Status s = sim::SimWorld::create(options, sim_world); !s) return s;
  sim::SimRobot robot(std::move(sim_world));
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(d.vx, d.vy, d.vth));
  sim::EpisodeOptions episode;
  episode.duration_s = duration_s;
  const double period_s = static_cast<double>(firmware->period_ns()) * 1e-9;
  const hal::Tick first = robot.current_tick();
  if (progress)
    episode.on_tick = [progress, period_s, first](hal::Tick tick, const sim::SimWorld& w,
                                                  const hal::SensorFrame&) {
      const Eigen::Isometry3d pose = w.torso_pose();
      const double yaw = yaw_of(pose);
      progress->yaw = progress->started
                          ? progress->yaw + std::remainder(yaw - progress->last_yaw, 2 * kPi)
                          : yaw;
      progress->last_yaw = yaw;
      const double t = static_cast<double>(tick - first) * period_s;
      if (!progress->started && t >= kSpeedFromS) {
        progress->from_position = pose.translation();
        progress->from_yaw = progress->yaw;
      }
      progress->started = true;
      progress->to_position = pose.translation();
      progress->to_yaw = progress->yaw;
    };
  result = sim::run_episode(
      robot,
      [&controller](const hal::SensorFrame& sensors, hal::Tick tick) {
        return controller.step(sensors, tick);
      },
      episode);
  if (result.status != sim::WorldStatus::kRunning)
    return Status::error("the simulation stopped: " + result.failure_reason);
  return {};
}

/// The speed along direction `k` (kDirections) over [kSpeedFromS, kSpeedToS]; none if it fell.
Status direction_speed(const sim::WorldOptions& world, std::size_t k, std::optional<double>& out) {
  sim::EpisodeResult result;
  Progress p;
  if (Status s = walk(world, kDirections[k], kSpeedToS, result, &p); !s) return s;
  out.reset();
  if (result.fell) return {};
  const Eigen::Vector3d moved = p.to_position - p.from_position;
  const double span = kSpeedToS - kSpeedFromS;
  const double along[6] = {
      moved.x(), -moved.x(), moved.y(), -moved.y(), p.to_yaw - p.from_yaw, p.from_yaw - p.to_yaw};
  out = along[k] / span;
  return {};
}

/// The largest impulse in direction `k` (kPushDirections) the forward walk survives.
Status largest_push(const sim::WorldOptions& world, std::size_t k, double& out) {
  const auto survives = [&world, k](double impulse, bool& ok) -> Status {
    sim::WorldOptions pushed = world;
    pushed.pushes = {sim::TorsoPush{kPushAtS, kPushDirections[k], impulse}};
    sim::EpisodeResult result;
    if (Status s = walk(pushed, kDirections[0], kPushAtS + kPushAfterS, result, nullptr); !s)
      return s;
    ok = !result.fell;
    return {};
  };
  double lo = 0.0, hi = kPushMax;
  bool ok = false;
  if (Status s = survives(hi, ok); !s) return s;
  if (ok) {
    out = hi;
    return {};
  }
  while (hi - lo > kPushResolution) {
    const double mid = 0.5 * (lo + hi);
    if (Status s = survives(mid, ok); !s) return s;
    (ok ? lo : hi) = mid;
  }
  out = lo;
  return {};
}

std::string cell(std::optional<double> v, const char* format) {
  if (!v) return "-";
  char text[32];
  std::snprintf(text, sizeof text, format, *v);
  return text;
}

}  // namespace

Status predict(const std::vector<const fw::FlightLog*>& logs, const sim::WorldOptions& world,
               const sim::ReplayOptions& replay, double& logged_peak_mps2, WorldPrediction& out) {
  out = {};
  logged_peak_mps2 = 0.0;
  sim::ReplayOptions options = replay;
  options.keep_traces = false;
  options.only_windows.clear();
  sim::WorldOptions replay_world = world;
  replay_world.imu.set_noise(false);  // the logged sensors carry the robot's noise
  for (const fw::FlightLog* log : logs) {
    sim::ReplayResult result;
    if (Status s = sim::replay_flight_log(*log, replay_world, options, result); !s) return s;
    for (const sim::ReplayWindow& w : result.windows) {
      if (!w.failure.empty()) continue;
      logged_peak_mps2 = std::max(logged_peak_mps2, w.errors.peak_accel_logged_mps2);
      out.replay_peak_accel_mps2 =
          std::max(out.replay_peak_accel_mps2, w.errors.peak_accel_sim_mps2);
    }
  }
  sim::EpisodeResult forward;
  if (Status s = walk(world, kDirections[0], kGoalWalkS, forward, nullptr); !s) return s;
  if (!forward.fell) out.time_to_goal_s = forward.time_to_goal_s;
  out.walk_peak_accel_mps2 = forward.max_accel;
  for (std::size_t k = 0; k < kDirections.size(); ++k)
    if (Status s = direction_speed(world, k, out.speed[k]); !s) return s;
  for (std::size_t k = 0; k < kPushNames.size(); ++k)
    if (Status s = largest_push(world, k, out.largest_push_n_s[k]); !s) return s;
  return {};
}

std::string prediction_table(double logged_peak_mps2, const WorldPrediction& nominal,
                             const WorldPrediction& calibrated) {
  std::string text =
      "prediction check (hold the nominal and the calibrated world against the robot):\n";
  char line[200];
  const auto row = [&](const std::string& figure, const std::string& logs, const std::string& n,
                       const std::string& c) {
    std::snprintf(line, sizeof line, "  %-34s %10s %10s %10s\n", figure.c_str(), logs.c_str(),
                  n.c_str(), c.c_str());
    text += line;
  };
  row("figure", "the logs", "nominal", "calibrated");
  row("peak |a| in the logs' replay [m/s^2]", cell(logged_peak_mps2, "%.2f"),
      cell(nominal.replay_peak_accel_mps2, "%.2f"),
      cell(calibrated.replay_peak_accel_mps2, "%.2f"));
  row("time to walk 2.5 m [s]", "", cell(nominal.time_to_goal_s, "%.2f"),
      cell(calibrated.time_to_goal_s, "%.2f"));
  row("that walk's peak |a| [m/s^2]", "", cell(nominal.walk_peak_accel_mps2, "%.2f"),
      cell(calibrated.walk_peak_accel_mps2, "%.2f"));
  for (std::size_t k = 0; k < kDirections.size(); ++k)
    row(std::string("speed ") + kDirections[k].name + (k < 4 ? " [m/s]" : " [rad/s]"), "",
        cell(nominal.speed[k], "%.3f"), cell(calibrated.speed[k], "%.3f"));
  for (std::size_t k = 0; k < kPushNames.size(); ++k)
    row(std::string("largest push ") + kPushNames[k] + " [N s]", "",
        cell(nominal.largest_push_n_s[k], "%.1f"), cell(calibrated.largest_push_n_s[k], "%.1f"));
  text +=
      "  (simulated: the default walk, noise on, seed 1; on the robot: a stopwatch over 2.5 m, a\n"
      "  walk along a tape, a pendulum push at the trunk)\n";
  return text;
}

}  // namespace stride::tools
