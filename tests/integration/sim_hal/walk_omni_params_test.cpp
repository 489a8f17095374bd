// The walk-omni run's chosen parameter file (firmware/config/walk-omni.json: the front member
// of optimiser/configs/walk-omni.json's full run, issue 22) drives the firmware in one
// direction per axis, 20 s on 10 noisy seeds, without a fall; only the turn goes the
// commanded way. It pins the world it was found in (the seed's: WorldPreset::kSeed) and the
// walk defaults of then (seed-walk.json).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "seeds.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace stride {
namespace {

const char* const kParams = STRIDE_SOURCE_DIR "/firmware/config/walk-omni.json";

/// One 20 s walk; `state` gets the motion state at its end.
sim::EpisodeResult walk(std::uint64_t seed, double vx, double vy, double vth,
                        fw::MotionState* state) {
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
  const sim::EpisodeResult result = sim::run_episode(robot, step, episode);
  *state = controller.motion().state();
  return result;
}

// Backward, left and turning left, 20 s on seeds 1-10: no fall and still walking at the end
// (counted with one to spare), and the turn turns left (the median; seeds 1-20 measured
// median 1.89 rad, IQR 0.29, 1.62-2.44; no fall, every walk still walking). Backward and left step
// but do not go the commanded way in this world (measured: backward ends 0.02-0.31 m *forward* on
// every seed; left ends 0.18 m left on seed 5 and 0.003-0.11 m *right* on the nine others: the
// issue-22 run found no feasible member, optimiser/README.md), so for them the test checks no more
// than that.
TEST(WalkOmniParams, BackwardAndLeftTwentySecondsWithoutAFallAndTheTurnTurnsOnTenSeeds) {
  struct Direction {
    const char* name;
    double vx, vy, vth;
  };
  for (const Direction d : {Direction{"backward", -1, 0, 0}, Direction{"left", 0, 1, 0},
                            Direction{"turn left", 0, 0, 1}}) {
    SCOPED_TRACE(d.name);
    int walking = 0;
    const test::Figures turned =
        test::Seeds(10).run(std::string(d.name) + ": turned [rad]", [&](std::uint64_t seed) {
          fw::MotionState state = fw::MotionState::kStand;
          const sim::EpisodeResult r = walk(seed, d.vx, d.vy, d.vth, &state);
          EXPECT_EQ(r.status, sim::WorldStatus::kRunning) << r.failure_reason;
          walking += !r.fell && state == fw::MotionState::kWalk ? 1 : 0;
          return r.turned_rad;
        });
    EXPECT_GE(walking, static_cast<int>(turned.size()) - 1) << "20 s without a fall, walking";
    if (d.vth > 0) {
      EXPECT_GT(turned.median(), 1.0);  // 1.89 rad, IQR 0.29 (seeds 1-20)
    }
  }
}

}  // namespace
}  // namespace stride
