// The walk engine in the Simbody simulation (issue 5 point 6): the firmware (Controller,
// motion manager, walk engine, safety layer) drives the simulated igus robot with the default
// (Ind_O) parameters and sensor noise on.
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

sim::EpisodeResult walk_in_sim(std::uint64_t seed, WalkCommand command, double duration_s,
                               const std::vector<fw::ParamWrite>& overrides = {},
                               double* yaw_out = nullptr, double* y_out = nullptr) {
  std::unique_ptr<fw::Firmware> firmware;
  EXPECT_TRUE(fw::Firmware::create({}, firmware));
  if (!overrides.empty()) {
    EXPECT_TRUE(firmware->params().set_now(overrides));
  }
  sim::WorldOptions options;
  options.seed = seed;
  options.imu = sim::ImuOptions::noisy();
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  const Status created = sim::SimWorld::create(options, world);
  EXPECT_TRUE(created) << created.message();
  sim::SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(command.vx, command.vy, command.vtheta));
  const sim::StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    return controller.step(sensors, tick);
  };
  sim::EpisodeOptions episode;
  episode.duration_s = duration_s;
  const sim::EpisodeResult result = sim::run_episode(robot, step, episode);
  const Eigen::Isometry3d torso = robot.world().ground_truth().torso;
  if (yaw_out != nullptr) {
    *yaw_out = std::atan2(torso.linear()(1, 0), torso.linear()(0, 0));
  }
  if (y_out != nullptr) *y_out = torso.translation().y();
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
