// The walk engine in the Simbody simulation (issue 5 point 6): the firmware (Controller,
// motion manager, walk engine, safety layer) drives the simulated igus robot with the default
// (Ind_O) parameters and sensor noise on.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride {
namespace {

struct WalkCommand {
  double vx = 0.0, vy = 0.0, vtheta = 0.0;
};

/// Where a walk ended, free of the step's sway: the torso yaw averaged over the last 2 s (two
/// and a bit steps; the torso yaws +-4 deg once per step pair) and the feet's midpoint.
struct WalkEnd {
  double mean_yaw = 0.0;              ///< [rad]
  double feet_x = 0.0, feet_y = 0.0;  ///< [m]
};

sim::EpisodeResult walk_in_sim(std::uint64_t seed, WalkCommand command, double duration_s,
                               const std::vector<fw::ParamWrite>& overrides = {},
                               double* yaw_out = nullptr, double* y_out = nullptr,
                               double left_hip_yaw_offset = 0.0, WalkEnd* end = nullptr,
                               bool seed_world = false) {
  std::unique_ptr<fw::Firmware> firmware;
  EXPECT_TRUE(fw::Firmware::create({}, firmware));
  // seed_world: the thesis's world and the firmware's walk defaults of then.
  if (seed_world) {
    EXPECT_TRUE(
        firmware->params().load_file_now(STRIDE_SOURCE_DIR "/firmware/config/seed-walk.json"));
  }
  if (!overrides.empty()) {
    EXPECT_TRUE(firmware->params().set_now(overrides));
  }
  sim::WorldOptions options;
  if (seed_world) options.apply(sim::WorldPreset::kSeed);
  options.seed = seed;
  options.imu.set_noise(true);
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  const Status created = sim::SimWorld::create(options, world);
  EXPECT_TRUE(created) << created.message();
  sim::SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(command.vx, command.vy, command.vtheta));
  const std::size_t hip_yaw = *firmware->servos().index_of("l_hip_yaw");
  const auto last_ticks = static_cast<hal::Tick>(std::llround((duration_s - 2.0) / 0.01));
  double yaw_sum = 0.0;
  int yaw_samples = 0;
  const sim::StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    if (end != nullptr && tick > last_ticks) {
      const Eigen::Isometry3d torso = robot.world().torso_pose();
      yaw_sum += std::atan2(torso.linear()(1, 0), torso.linear()(0, 0));
      ++yaw_samples;
    }
    hal::CommandFrame commands = controller.step(sensors, tick);
    // A disturbance the walk does not know of: the left hip yaw servo off by a fixed angle
    // (a miscalibrated zero), which turns every left step.
    commands.servos[hip_yaw].position_rad += left_hip_yaw_offset;
    return commands;
  };
  sim::EpisodeOptions episode;
  episode.duration_s = duration_s;
  const sim::EpisodeResult result = sim::run_episode(robot, step, episode);
  const Eigen::Isometry3d torso = robot.world().ground_truth().torso;
  if (yaw_out != nullptr) {
    *yaw_out = std::atan2(torso.linear()(1, 0), torso.linear()(0, 0));
  }
  if (y_out != nullptr) *y_out = torso.translation().y();
  if (end != nullptr) {
    const sim::GroundTruth truth = robot.world().ground_truth();
    end->mean_yaw = yaw_samples > 0 ? yaw_sum / yaw_samples : 0.0;
    end->feet_x = 0.5 * (truth.left_foot.translation().x() + truth.right_foot.translation().x());
    end->feet_y = 0.5 * (truth.left_foot.translation().y() + truth.right_foot.translation().y());
  }
  return result;
}

void print(const char* what, std::uint64_t seed, const sim::EpisodeResult& r) {
  std::printf(
      "  %s seed %llu: fell %d (%.2f s) distance %.3f m time_to_goal %s max|a| %.2f "
      "m/s^2 sim %.1f s rtf %.1f\n",
      what, static_cast<unsigned long long>(seed), r.fell ? 1 : 0, r.fall_time_s, r.distance_m,
      r.time_to_goal_s ? std::to_string(*r.time_to_goal_s).c_str() : "never", r.max_accel,
      r.sim_time_s, r.rtf);
}

// Issue 5 asks for 10 of 10 seeds forward and 20 s backward, sideways and turning without a
// fall. With the balance defaults of firmware/src/walk/README.md (gyro rate and torso tilt
// feedback) the simulated robot reaches 2.5 m in all 10 seeds (held-out seeds 11..30: 20 of 20)
// and stays up for 20 s backward, sideways and turning on the spot (seed 1), moving sideways
// the commanded way (final torso y 0.136 m left, -0.080 m right; the torso rocks about
// +-0.12 m laterally, see firmware/src/walk/README.md). The walk is still sensitive to small
// changes (the parameters were found by a search), so a change that makes it worse fails here.
constexpr int kForwardSeedsFloor = 10;  // of 10

TEST(WalkInSim, ForwardTwoAndAHalfMetresInAllSeedsAndFasterThanTheSeed) {
  int reached = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const sim::EpisodeResult r = walk_in_sim(seed, {1.0, 0.0, 0.0}, 60.0);
    print("forward", seed, r);
    EXPECT_EQ(r.status, sim::WorldStatus::kRunning) << r.failure_reason;
    if (r.fell || !r.time_to_goal_s) continue;
    ++reached;
    // Where it arrives it beats the seed's Ind_O (32.5 s, peak |a| 70.75 m/s^2).
    EXPECT_LT(*r.time_to_goal_s, 32.5) << "seed " << seed;
    EXPECT_LT(r.max_accel, 70.75) << "seed " << seed;
  }
  std::printf("  forward 2.5 m reached in %d of 10 seeds (issue target: 10)\n", reached);
  EXPECT_GE(reached, kForwardSeedsFloor);
}

TEST(WalkInSim, SidewaysBothWaysTwentySecondsWithoutFalling) {
  for (const double vy : {1.0, -1.0}) {
    double y = 0.0;
    const sim::EpisodeResult r = walk_in_sim(1, {0.0, vy, 0.0}, 20.0, {}, nullptr, &y);
    print(vy > 0 ? "left" : "right", 1, r);
    EXPECT_FALSE(r.fell) << "vy " << vy;
    EXPECT_GE(r.sim_time_s, 20.0 - 0.011) << "vy " << vy;
    EXPECT_GT(y * vy, 0.05) << "did not step sideways the commanded way: y " << y;
  }
}

// Backward and turning on the spot (both ways): 20 s without a fall, the world healthy.
TEST(WalkInSim, BackwardAndTurningTwentySecondsWithoutFalling) {
  for (const WalkCommand command :
       {WalkCommand{-1.0, 0.0, 0.0}, WalkCommand{0.0, 0.0, 1.0}, WalkCommand{0.0, 0.0, -1.0}}) {
    double yaw = 0.0;
    const sim::EpisodeResult r = walk_in_sim(1, command, 20.0, {}, &yaw);
    print(command.vx < 0 ? "backward" : (command.vtheta > 0 ? "turn left" : "turn right"), 1, r);
    EXPECT_EQ(r.status, sim::WorldStatus::kRunning) << r.failure_reason;
    EXPECT_FALSE(r.fell) << "vx " << command.vx << " vtheta " << command.vtheta;
    EXPECT_GE(r.sim_time_s, 20.0 - 0.011);
    std::printf("  final yaw %.3f rad\n", yaw);
  }
}

}  // namespace
}  // namespace stride

namespace stride {
namespace {

// Heading hold (walk.balance.heading_*, gain 0.5 by default since issue 29; these tests set it
// on or off themselves; firmware/src/walk/README.md has the measurements behind the settings
// used here).
const std::vector<fw::ParamWrite> kHoldOn{{"walk.balance.heading_gain", 0.5},
                                          {"walk.balance.heading_max_correction", 0.3}};
constexpr double kDeg = 180.0 / 3.141592653589793;

// The stock forward walk, 20 s, seeds 1..10: with the hold on no seed ends more than 5 deg off
// its start heading (mean over the last 2 s; measured worst 4.4 deg, the hold off 7.7 deg) and
// the feet end within 0.08 m of the start line (measured 0.035 m; the hold off 0.118 m).
// Pins the seed's world and walk (issue 22's measurement). In the faithful default world the
// closed-loop walk with the same hold ends up to 17.8 deg off and its feet up to 0.50 m to the
// side (seeds 1-10): the straightness of issue 29 point 5, not met there.
TEST(WalkHeadingHold, StockForwardWalkStaysOnItsHeading) {
  double worst_yaw = 0.0, worst_y = 0.0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    WalkEnd e;
    const sim::EpisodeResult r =
        walk_in_sim(seed, {1.0, 0.0, 0.0}, 20.0, kHoldOn, nullptr, nullptr, 0.0, &e, true);
    std::printf("  seed %llu: fell %d distance %.3f m feet y %.3f m mean yaw %.2f deg\n",
                static_cast<unsigned long long>(seed), r.fell ? 1 : 0, r.distance_m, e.feet_y,
                e.mean_yaw * kDeg);
    EXPECT_FALSE(r.fell) << "seed " << seed;
    EXPECT_GT(r.distance_m, 1.5) << "seed " << seed;
    worst_yaw = std::max(worst_yaw, std::abs(e.mean_yaw));
    worst_y = std::max(worst_y, std::abs(e.feet_y));
  }
  std::printf("  worst: yaw %.2f deg, feet y %.3f m\n", worst_yaw * kDeg, worst_y);
  EXPECT_LT(worst_yaw * kDeg, 5.0);
  EXPECT_LT(worst_y, 0.08);
}

// A disturbance the walk does not model: the left hip yaw servo 0.1 rad off its zero. Without
// the hold the robot turns right by 7.4 deg in 20 s (seed 5); the hold keeps it within 3.5 deg.
TEST(WalkHeadingHold, CorrectsAHipYawDisturbanceTheOpenWalkTurnsWith) {
  WalkEnd on, off;
  const sim::EpisodeResult r_on =
      walk_in_sim(5, {1.0, 0.0, 0.0}, 20.0, kHoldOn, nullptr, nullptr, 0.1, &on);
  const sim::EpisodeResult r_off = walk_in_sim(
      5, {1.0, 0.0, 0.0}, 20.0, {{"walk.balance.heading_gain", 0.0}}, nullptr, nullptr, 0.1, &off);
  std::printf("  hold on: yaw %.2f deg feet y %.3f m; hold off: yaw %.2f deg feet y %.3f m\n",
              on.mean_yaw * kDeg, on.feet_y, off.mean_yaw * kDeg, off.feet_y);
  EXPECT_FALSE(r_on.fell);
  EXPECT_FALSE(r_off.fell);
  EXPECT_GT(std::abs(off.mean_yaw) * kDeg, 6.0);
  EXPECT_LT(std::abs(on.mean_yaw) * kDeg, 3.5);
  EXPECT_LT(std::abs(on.mean_yaw), 0.5 * std::abs(off.mean_yaw));
}

}  // namespace
}  // namespace stride
