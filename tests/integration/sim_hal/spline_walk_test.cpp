// The spline walk (walk.engine 1, firmware defaults) in the world `stride sim` ships (the
// faithful world, noise on, its default physics step), judged over seeds: in every direction
// it walks the commanded way without falling, on Simbody and on MuJoCo. Speeds are measured
// from the simulator's ground truth between 4 s (after the start blend, the steps in place and
// the acceleration) and the end. STRIDE_TEST_SEEDS=20 judges 20 seeds instead of 5, and each
// row prints its median, interquartile range and falls: how the limits below were measured.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"
#include "stride/sim_hal/world_spec.hpp"

namespace stride {
namespace {

constexpr double kMeasureFrom = 4.0;  // [s]
constexpr double kDuration = 10.0;    // [s]

struct Direction {
  const char* name;
  double vx, vy, vtheta;
};

struct Walked {
  bool fell = false;
  double along = 0.0;  ///< speed along the command [m/s] or turn rate [rad/s] from 4 s on
};

double yaw_of(const Eigen::Isometry3d& pose) {
  return std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
}

Walked walk(const Direction& d, std::uint64_t seed, sim::EngineKind engine, int walk_engine) {
  std::unique_ptr<fw::Firmware> firmware;
  EXPECT_TRUE(fw::Firmware::create({}, firmware));
  EXPECT_TRUE(firmware->params().set_now({{"walk.engine", walk_engine}}));
  sim::WorldSpec spec;
  spec.engine = engine;
  spec.seed = seed;
  sim::WorldOptions options = spec.to_options();
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  const Status created = sim::SimWorld::create(options, world);
  EXPECT_TRUE(created) << created.message();
  sim::SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(d.vx, d.vy, d.vtheta));
  const auto from_tick = static_cast<hal::Tick>(std::llround(kMeasureFrom / 0.01));
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  double yaw = 0.0, previous_yaw = 0.0;  // unwrapped from the measurement's start
  const sim::StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    if (tick >= from_tick) {
      const Eigen::Isometry3d torso = robot.world().torso_pose();
      if (tick == from_tick) start = torso, previous_yaw = yaw_of(torso);
      const double now = yaw_of(torso);
      yaw += std::remainder(now - previous_yaw, 2.0 * M_PI);
      previous_yaw = now;
    }
    return controller.step(sensors, tick);
  };
  sim::EpisodeOptions episode;
  episode.duration_s = kDuration;
  const sim::EpisodeResult result = sim::run_episode(robot, step, episode);
  Walked out;
  out.fell = result.fell;
  if (result.fell) return out;
  const Eigen::Isometry3d end = robot.world().torso_pose();
  const double span = kDuration - kMeasureFrom;
  const double heading = yaw_of(start);
  const Eigen::Vector3d moved = end.translation() - start.translation();
  const double forward = std::cos(heading) * moved.x() + std::sin(heading) * moved.y();
  const double left = -std::sin(heading) * moved.x() + std::cos(heading) * moved.y();
  if (d.vtheta != 0.0) {
    out.along = std::copysign(1.0, d.vtheta) * yaw / span;
  } else if (d.vy != 0.0) {
    out.along = std::copysign(1.0, d.vy) * left / span;
  } else {
    out.along = std::copysign(1.0, d.vx) * forward / span;
  }
  return out;
}

struct Judged {
  int falls = 0;
  double median = 0.0;  ///< of the runs that did not fall
};

int seeds_to_judge() {
  const char* text = std::getenv("STRIDE_TEST_SEEDS");
  const int n = text != nullptr ? std::atoi(text) : 0;
  return n >= 5 ? n : 5;
}

double quantile(const std::vector<double>& sorted, double q) {
  const double at = q * static_cast<double>(sorted.size() - 1);
  const auto i = static_cast<std::size_t>(at);
  const double w = at - static_cast<double>(i);
  return i + 1 < sorted.size() ? (1 - w) * sorted[i] + w * sorted[i + 1] : sorted[i];
}

Judged judge(const Direction& d, sim::EngineKind engine, int walk_engine = 1) {
  const int seeds = seeds_to_judge();
  Judged j;
  std::vector<double> speeds;
  for (int s = 1; s <= seeds; ++s) {
    const Walked w = walk(d, static_cast<std::uint64_t>(s), engine, walk_engine);
    if (w.fell) {
      ++j.falls;
    } else {
      speeds.push_back(w.along);
    }
  }
  if (!speeds.empty()) {
    std::sort(speeds.begin(), speeds.end());
    j.median = quantile(speeds, 0.5);
    std::printf("%s %s: median %.3f, IQR %.3f, falls %d of %d\n", sim::to_string(engine), d.name,
                j.median, quantile(speeds, 0.75) - quantile(speeds, 0.25), j.falls, seeds);
  }
  return j;
}

// Limits: at most 1 fall in 5 seeds (measured: none in 20 on either engine), and a median
// speed below the 20-seed median by the larger of 10 % and 3 interquartile ranges.
struct Row {
  Direction direction;
  double limit;  ///< [m/s] or [rad/s]
};

void expect_walks(const Row& row, sim::EngineKind engine) {
  const Judged j = judge(row.direction, engine);
  EXPECT_LE(j.falls, 1) << row.direction.name;
  EXPECT_GT(j.median, row.limit) << row.direction.name;
}

TEST(SplineWalk, WalksEveryDirectionOnSimbodyWithItsDefaults) {
  // Measured over seeds 1-20 (median, IQR): forward 0.245, 0.004 m/s; backward 0.182, 0.005;
  // left 0.097, 0.004; right 0.096, 0.006; turn left 0.611, 0.044 rad/s; right 0.602, 0.024.
  const Row rows[] = {
      {{"forward", 1, 0, 0}, 0.22},   {{"backward", -1, 0, 0}, 0.16},
      {{"left", 0, 1, 0}, 0.085},     {{"right", 0, -1, 0}, 0.078},
      {{"turn left", 0, 0, 1}, 0.47}, {{"turn right", 0, 0, -1}, 0.53},
  };
  for (const Row& row : rows) expect_walks(row, sim::EngineKind::kSimbody);
}

TEST(SplineWalk, WalksForwardSidewaysAndTurnsOnMujoco) {
  // Measured over seeds 1-20 (median, IQR): forward 0.335, 0.005 m/s; left 0.120, 0.007;
  // turn right 0.777, 0.036 rad/s.
  const Row rows[] = {
      {{"forward", 1, 0, 0}, 0.30},
      {{"left", 0, 1, 0}, 0.099},
      {{"turn right", 0, 0, -1}, 0.66},
  };
  for (const Row& row : rows) expect_walks(row, sim::EngineKind::kMujoco);
}

}  // namespace
}  // namespace stride
