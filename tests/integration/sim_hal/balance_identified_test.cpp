// The balance re-tuned on the identified MX servo and the CM730 IMU chain (issue 20 point 5):
// firmware/config/balance-identified.json (walk.balance.* only; the 46 genome parameters stay
// at Ind_O) drives the firmware in the world of `--servo-law identified --imu cm730 --noise on`.
// With this file: forward, backward, sideways and turning both ways hold (do not fall; only
// forward and the turns go the commanded way), and the forward walk holds on robots that differ
// from the model, judged over seeds (tests/README.md). The stock balance falls there in every
// seed within 7 s, and the file holds at every step from 5 ms to 0.25 ms: figures of the
// benchmark (firmware/src/walk/README.md and tests/bench/RESULTS.md), not asserted here.
// It pins the world and walk of issue 20: the seed's 2 cm grass, and the firmware's walk
// defaults of then (firmware/config/seed-walk.json: no compliance feed-forward, no support
// exchange at touchdown, no heading hold) under the file. The faithful default world of
// issue 29 (turf, those on) is walk_compliance_test.cpp's.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "robot_variants.hpp"
#include "seeds.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/robot_model.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "temp_dir.hpp"

namespace stride {
namespace {

const char* const kParams = STRIDE_SOURCE_DIR "/firmware/config/balance-identified.json";
const char* const kSeedWalk = STRIDE_SOURCE_DIR "/firmware/config/seed-walk.json";

struct Walk {
  double vx = 0.0, vy = 0.0, vth = 0.0;
};

sim::WorldOptions identified_world(std::uint64_t seed, std::int64_t step_us) {
  sim::WorldOptions options;
  options.seed = seed;
  options.servo.law = sim::ServoLaw::kIdentified;
  options.imu.set_noise(true);
  options.imu.chain = sim::ImuChain{};  // the chips and the CM730, their own noise on
  options.imu.chain.noise = true;
  options.physics_step_ns = step_us * 1000;
  options.contact = sim::ContactOptions::seed();
  return options;
}

/// One walk episode; `state` (if given) gets the motion state at its end. `stop_at_goal` ends
/// it once the torso has covered 2.5 m.
sim::EpisodeResult walk(sim::WorldOptions options, Walk command, double duration_s,
                        bool tuned = true, fw::MotionState* state = nullptr,
                        bool stop_at_goal = false) {
  std::unique_ptr<fw::Firmware> firmware;
  EXPECT_TRUE(fw::Firmware::create({}, firmware));
  const Status seed_walk = firmware->params().load_file_now(kSeedWalk);
  EXPECT_TRUE(seed_walk) << seed_walk.message();
  if (tuned) {
    const Status loaded = firmware->params().load_file_now(kParams);
    EXPECT_TRUE(loaded) << loaded.message();
  }
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  const Status created = sim::SimWorld::create(options, world);
  EXPECT_TRUE(created) << created.message();
  sim::SimRobot robot(std::move(world));
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(command.vx, command.vy, command.vth));
  const sim::StepFunction step = [&](const hal::SensorFrame& sensors, hal::Tick tick) {
    return controller.step(sensors, tick);
  };
  sim::EpisodeOptions episode;
  episode.duration_s = duration_s;
  episode.stop_at_goal = stop_at_goal;
  const sim::EpisodeResult result = sim::run_episode(robot, step, episode);
  if (state != nullptr) *state = controller.motion().state();
  return result;
}

/// Reached 2.5 m forward before any fall, within 40 s.
bool reaches_the_goal(const sim::EpisodeResult& r) {
  return r.status == sim::WorldStatus::kRunning && r.time_to_goal_s &&
         (!r.fell || *r.time_to_goal_s < r.fall_time_s);
}

// Forward to 2.5 m on noisy seeds at the default 2 ms step, where the stock balance reaches it
// in none. Measured 2026-11-28, seeds 1-20: 20 of 20 reach it (the benchmark,
// bench_sim_hal_step_independence, covers the steps from 5 to 0.25 ms; this test ran 0.5 ms too
// before tests/README.md's rule 5). A count with one to spare.
TEST(BalanceIdentified, ForwardReachesTheGoalOnNoisySeeds) {
  const test::Seeds seeds(10);
  const test::Count reached = seeds.count("forward 2.5 m before a fall", [](std::uint64_t seed) {
    return reaches_the_goal(
        walk(identified_world(seed, 2000), {1, 0, 0}, 40.0, true, nullptr, true));
  });
  EXPECT_GE(reached.k, reached.n - 1);
}

// Backward, sideways both ways and turning both ways: 20 s without a fall, still walking at the
// end, on seeds 1-5. Only the turns move the commanded way (backward and sideways step but do
// not go where they are commanded: the walk README's "sideways does not move sideways", figures
// in tests/bench/RESULTS.md), so for the others the test checks no more than that.
// Measured 2026-11-28, seeds 1-20 (20 s): every direction 20 of 20 without a fall and walking;
// turned left median 0.475 rad (IQR 0.030), right -0.177 rad (IQR 0.025); backward, left and right
// turned 0.004, 0.003 and -0.001 rad.
TEST(BalanceIdentified, BackwardAndSidewaysTwentySecondsWithoutAFallAndTheTurnsTurn) {
  struct Direction {
    const char* name;
    Walk command;
  };
  for (const Direction d : {Direction{"backward", {-1, 0, 0}}, Direction{"left", {0, 1, 0}},
                            Direction{"right", {0, -1, 0}}, Direction{"turn left", {0, 0, 1}},
                            Direction{"turn right", {0, 0, -1}}}) {
    SCOPED_TRACE(d.name);
    int walking = 0;
    const std::vector<test::Figures> f =
        test::Seeds(5).run({"fell", "turned [rad]"}, [&](std::uint64_t seed) {
          fw::MotionState state = fw::MotionState::kStand;
          const sim::EpisodeResult r =
              walk(identified_world(seed, 2000), d.command, 20.0, true, &state);
          EXPECT_EQ(r.status, sim::WorldStatus::kRunning) << r.failure_reason;
          walking += !r.fell && state == fw::MotionState::kWalk ? 1 : 0;  // stepping, standing
          return std::vector<double>{r.fell ? 1.0 : 0.0, r.turned_rad};
        });
    const int n = static_cast<int>(f[0].size());
    EXPECT_GE(walking, n - 1) << "without a fall and still walking";
    if (d.command.vth > 0) {
      EXPECT_GT(f[1].median(), 0.30);  // 0.475 rad, IQR 0.030 (seeds 1-20; seed 1: 0.49)
    }
    if (d.command.vth < 0) {
      EXPECT_LT(f[1].median(), -0.10);  // -0.177 rad, IQR 0.025 (seeds 1-20; seed 1: -0.18)
    }
  }
}

// Robots that differ from the model as real ones do (sim_hal/models/make_variants.py: trunk
// +-10 %, its centre of mass 1 cm off each way, one leg 5 % heavier): forward to 2.5 m, with no
// fall before the goal (2 ms step), on 5 seeds each, 40 runs in all. It asserted 10 of 10 seeds
// on each robot; with gravity 1e-5 stronger, seed 9 on the CoM 1 cm left fell (issue 55), so
// "every seed" was a draw. Measured 2026-11-28, seeds 1-20 of each: 158 of 160, the CoM 1 cm
// right 18 of 20 (seeds 16 and 19 too slow or fell), every other robot 20 of 20. Counts with one
// to spare below those shares (test::count_limit): per robot from the worst robot's 90 %, over
// all from 158 of 160.
TEST(BalanceIdentified, ForwardReachesTheGoalOnRobotsThatDifferFromTheModel) {
  test::TempDir tmp;
  int code = -1;
  const std::string out = test::write_robot_variants(tmp.path(), code);
  ASSERT_EQ(code, 0) << out;
  int reached = 0, runs = 0;
  for (const char* name : test::kRobotVariants) {
    const std::filesystem::path urdf = tmp.path() / (std::string(name) + ".urdf");
    auto model = std::make_shared<sim::RobotModel>();
    const Status loaded = sim::RobotModel::load_file(urdf, *model);
    ASSERT_TRUE(loaded) << loaded.message();
    const test::Count c = test::Seeds(5).count(name, [&](std::uint64_t seed) {
      sim::WorldOptions options = identified_world(seed, 2000);
      options.urdf = urdf;
      options.model = model;
      return reaches_the_goal(walk(options, {1, 0, 0}, 40.0, true, nullptr, true));
    });
    EXPECT_GE(c.k, test::count_limit(0.9, c.n)) << name;
    reached += c.k;
    runs += c.n;
  }
  std::printf("  2.5 m in %d of %d runs\n", reached, runs);
  EXPECT_GE(reached, test::count_limit(158.0 / 160.0, runs));
}

}  // namespace
}  // namespace stride
