// The spline walk (walk.engine 1, firmware defaults) in the world `stride sim` ships (the
// faithful world, noise on, its default physics step), judged over seeds: in every direction
// it walks the commanded way without falling, on Simbody and on MuJoCo. Speeds are measured
// from the simulator's ground truth between 4 s (after the start blend, the steps in place and
// the acceleration) and the end, over seeds (tests/README.md; STRIDE_TEST_SEEDS=20 re-measures
// the figures beside the limits).
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "seeds.hpp"
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

// Limits: at most 1 fall in 5 seeds (measured: none in 20 on either engine), and a median
// speed below the 20-seed median by the larger of 10 % and 3 interquartile ranges. A fallen
// run's speed counts as 0 in the median.
struct Row {
  Direction direction;
  double limit;  ///< [m/s] or [rad/s]
};

void expect_walks(const Row& row, sim::EngineKind engine) {
  const test::Seeds seeds(5);
  std::vector<Walked> runs;
  const test::Count upright = seeds.count(row.direction.name, [&](std::uint64_t seed) {
    runs.push_back(walk(row.direction, seed, engine, 1));
    return !runs.back().fell;
  });
  EXPECT_GE(upright.k, upright.n - 1) << row.direction.name;
  std::size_t i = 0;
  const test::Figures speed = seeds.run(std::string(row.direction.name) + " speed",
                                        [&](std::uint64_t) { return runs[i++].along; });
  EXPECT_GT(speed.median(), row.limit) << row.direction.name;
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
