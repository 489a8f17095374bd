// The walk engine in the Simbody simulation (issue 5 point 6): the firmware (Controller,
// motion manager, walk engine, safety layer) drives the simulated igus robot with the default
// (Ind_O) parameters and sensor noise on. Forward 2.5 m in 10 of 10 seeds; backward, sideways
// and turning on the spot for 20 s each without falling.
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
                               double* yaw_out = nullptr) {
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
  (void)yaw_out;
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

TEST(WalkInSim, ForwardTwoAndAHalfMetresInTenOfTenSeeds) {
  int reached = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const sim::EpisodeResult r = walk_in_sim(seed, {1.0, 0.0, 0.0}, 60.0);
    print("forward", seed, r);
    EXPECT_FALSE(r.fell) << "seed " << seed;
    EXPECT_TRUE(r.time_to_goal_s.has_value()) << "seed " << seed;
    if (!r.fell && r.time_to_goal_s) ++reached;
  }
  std::printf("  forward 2.5 m reached in %d of 10 seeds\n", reached);
}

TEST(WalkInSim, BackwardSidewaysAndTurningTwentySecondsEach) {
  struct Case {
    const char* name;
    WalkCommand command;
  };
  for (const Case& c : {Case{"backward", {-1.0, 0.0, 0.0}}, Case{"sideways", {0.0, 1.0, 0.0}},
                        Case{"turning", {0.0, 0.0, 1.0}}}) {
    const sim::EpisodeResult r = walk_in_sim(1, c.command, 20.0);
    print(c.name, 1, r);
    EXPECT_FALSE(r.fell) << c.name;
    EXPECT_GE(r.sim_time_s, 20.0 - 0.011) << c.name;
  }
}

}  // namespace
}  // namespace stride
