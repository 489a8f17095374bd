// The walk-omni run's chosen parameter file (firmware/config/walk-omni.json: the front member
// of optimiser/configs/walk-omni.json's full run, issue 22) drives the firmware in every
// direction: one direction per axis, 20 s on 10 noisy seeds, no fall. It pins the world it was
// found in (the seed's: WorldPreset::kSeed) and the walk defaults of then (seed-walk.json).
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace stride {
namespace {

const char* const kParams = STRIDE_SOURCE_DIR "/firmware/config/walk-omni.json";

sim::EpisodeResult walk(std::uint64_t seed, double vx, double vy, double vth) {
  std::unique_ptr<fw::Firmware> firmware;
  EXPECT_TRUE(fw::Firmware::create({}, firmware));
  EXPECT_TRUE(
      firmware->params().load_file_now(STRIDE_SOURCE_DIR "/firmware/config/seed-walk.json"));
  const Status loaded = firmware->params().load_file_now(kParams);
  EXPECT_TRUE(loaded) << loaded.message();
  sim::WorldOptions options = sim::WorldOptions::seed_world();
  options.seed = seed;
  options.imu.set_noise(true);
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  EXPECT_TRUE(sim::SimWorld::create(options, world));
  sim::SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(vx, vy, vth));
  const sim::StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    return controller.step(sensors, tick);
  };
  sim::EpisodeOptions episode;
  episode.duration_s = 20.0;
  return sim::run_episode(robot, step, episode);
}

TEST(WalkOmniParams, BackwardSidewaysAndTurningTwentySecondsOnTenSeeds) {
  struct Direction {
    const char* name;
    double vx, vy, vth;
  };
  for (const Direction d : {Direction{"backward", -1, 0, 0}, Direction{"left", 0, 1, 0},
                            Direction{"turn left", 0, 0, 1}}) {
    int survived = 0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      const sim::EpisodeResult r = walk(seed, d.vx, d.vy, d.vth);
      EXPECT_FALSE(r.fell) << d.name << ", seed " << seed << " at " << r.sim_time_s << " s";
      EXPECT_EQ(r.status, sim::WorldStatus::kRunning) << r.failure_reason;
      survived += r.fell ? 0 : 1;
    }
    std::printf("walk-omni.json %s: %d/10 seeds 20 s without a fall\n", d.name, survived);
  }
}

}  // namespace
}  // namespace stride
