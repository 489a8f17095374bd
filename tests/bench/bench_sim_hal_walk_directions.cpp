// Walk in every direction (issue 29 points 2, 4, 5, 7): per direction (forward, backward, left,
// right, turning left and right) and seed, a 20 s walk from standing; prints falls, the median
// over seeds of the speed over 5-20 s (m/s along the commanded axis in the start frame; rad/s
// turning), the drift across it as a share of the distance, the heading change, and the swing
// foot's clearance over the grass: per step, the highest the swing foot's lowest stud rose
// above where it stood (median and 10th percentile over the steps of every walk), and the share
// of steps whose swing foot still touched the grass at mid-swing. Every figure is deterministic.
// Run: build/release/bench/bench_sim_hal_walk_directions [--seeds N] [--duration S]
//      [--params FILE] [--directions fwd,back,left,right,turn_l,turn_r] [world options]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "stride/core/cli_args.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_cli.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/swing_clearance.hpp"

namespace {

namespace fw = stride::fw;
namespace core = stride::core;
namespace hal = stride::hal;
namespace sim = stride::sim;

struct Direction {
  const char* name;
  double vx, vy, vth;
};

constexpr Direction kDirections[] = {{"fwd", 1, 0, 0},    {"back", -1, 0, 0},
                                     {"left", 0, 1, 0},   {"right", 0, -1, 0},
                                     {"turn_l", 0, 0, 1}, {"turn_r", 0, 0, -1}};

struct WalkFigures {
  bool fell = false;
  double speed = 0.0;    ///< along the commanded axis [m/s] or turning [rad/s], 5 s to the end
  double drift = 0.0;    ///< |across| / |along| over the same span (translations)
  double heading = 0.0;  ///< heading change over the walk [rad]
  std::vector<double> clearance;  ///< per step [m]
  int steps = 0, grazing = 0;
};

double yaw_of(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d r = pose.linear();
  return std::atan2(r(1, 0), r(0, 0));
}

WalkFigures walk(const fw::FirmwareOptions& firmware_options, sim::WorldOptions options,
                 std::uint64_t seed, const Direction& d, double duration) {
  std::unique_ptr<fw::Firmware> firmware;
  if (const stride::Status s = fw::Firmware::create(firmware_options, firmware); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    std::exit(2);
  }
  options.seed = seed;
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  if (const stride::Status s = sim::SimWorld::create(options, world); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    std::exit(2);
  }
  sim::SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(d.vx, d.vy, d.vth));
  WalkFigures out;
  const double period = static_cast<double>(firmware->period_ns()) * 1e-9;
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity(), at5 = start;
  double yaw_unwrapped = 0.0, previous_yaw = 0.0, yaw5 = 0.0;
  sim::SwingClearance clearance;
  const sim::StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    const sim::GroundTruth g = robot.world().ground_truth();
    const double t = static_cast<double>(tick) * period;
    const double yaw = yaw_of(g.torso);
    if (tick == 0) {
      start = g.torso;
      previous_yaw = yaw;
    }
    yaw_unwrapped += std::remainder(yaw - previous_yaw, 2.0 * M_PI);
    previous_yaw = yaw;
    if (std::abs(t - 5.0) < 0.5 * period) {
      at5 = g.torso;
      yaw5 = yaw_unwrapped;
    }
    clearance.observe(t, g);
    return controller.step(sensors, tick);
  };
  sim::EpisodeOptions episode;
  episode.duration_s = duration;
  const sim::EpisodeResult result = sim::run_episode(robot, step, episode);
  out.fell = result.fell;
  out.clearance = clearance.clearance();
  out.steps = clearance.steps();
  out.grazing = clearance.grazing_steps();
  const Eigen::Isometry3d end = robot.world().torso_pose();
  const double span = result.sim_time_s - 5.0;
  out.heading = yaw_unwrapped;
  if (span > 1.0) {
    // Displacement over 5 s .. end in the start frame's axes.
    const Eigen::Vector3d move =
        start.linear().transpose() * (end.translation() - at5.translation());
    if (d.vth != 0.0) {
      out.speed = (yaw_unwrapped - yaw5) / span;
    } else {
      const bool sagittal = d.vx != 0.0;
      const double along = sagittal ? move.x() : move.y();
      const double across = sagittal ? move.y() : move.x();
      out.speed = along / span;
      out.drift = std::abs(along) > 1e-6 ? std::abs(across) / std::abs(along) : 0.0;
    }
  }
  return out;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::floor(p * static_cast<double>(v.size() - 1)))];
}

}  // namespace

int main(int argc, char** argv) {
  core::CliArgs args;
  args.option("seeds", "seeds per direction", true, "3");
  args.option("duration", "walk length [s]", true, "20");
  args.option("directions", "comma-separated: fwd,back,left,right,turn_l,turn_r", true,
              "fwd,back,left,right,turn_l,turn_r");
  args.option("params", "firmware parameter file (JSON) applied after the defaults", true);
  sim::declare_world_options(args);
  if (const stride::Status s = args.parse(argc, argv); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    return 2;
  }
  sim::WorldOptions base;
  if (const stride::Status s = sim::read_world_options(args, base); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    return 2;
  }
  fw::FirmwareOptions firmware;
  if (args.has("params")) firmware.params_file = args.get("params");
  std::int64_t seeds = 3;
  double duration = 20.0;
  if (!args.get_int("seeds", seeds) || seeds < 1 || !args.get_double("duration", duration) ||
      !(duration > 6.0)) {
    std::fprintf(stderr, "--seeds must be >= 1 and --duration > 6 s\n");
    return 2;
  }
  std::vector<std::string> wanted;
  std::stringstream list(args.get("directions"));
  for (std::string item; std::getline(list, item, ',');) wanted.push_back(item);
  std::printf("%s, %lld seeds, %.0f s, params %s\n", sim::describe_world(base).c_str(),
              static_cast<long long>(seeds), duration,
              args.has("params") ? args.get("params").c_str() : "default");
  std::printf("%-7s %5s %10s %7s %9s %9s %9s %7s\n", "dir", "falls", "speed_med", "drift",
              "heading", "clear_med", "clear_p10", "grazing");
  for (const Direction& d : kDirections) {
    if (std::find(wanted.begin(), wanted.end(), d.name) == wanted.end()) continue;
    int falls = 0, steps = 0, grazing = 0;
    std::vector<double> speeds, drifts, headings, clearance;
    for (std::int64_t s = 1; s <= seeds; ++s) {
      const WalkFigures w = walk(firmware, base, static_cast<std::uint64_t>(s), d, duration);
      falls += w.fell ? 1 : 0;
      speeds.push_back(w.speed);
      drifts.push_back(w.drift);
      headings.push_back(std::abs(w.heading));
      clearance.insert(clearance.end(), w.clearance.begin(), w.clearance.end());
      steps += w.steps;
      grazing += w.grazing;
    }
    std::printf("%-7s %2d/%-2lld %10.3f %7.2f %9.3f %9.4f %9.4f %3d/%-3d\n", d.name, falls,
                static_cast<long long>(seeds), percentile(speeds, 0.5), percentile(drifts, 1.0),
                percentile(headings, 1.0), percentile(clearance, 0.5), percentile(clearance, 0.1),
                grazing, steps);
    std::fflush(stdout);
  }
  return 0;
}
