// The balance re-tuned on the identified MX servo and the CM730 IMU chain (issue 20 point 5):
// firmware/config/balance-identified.json (walk.balance.* only; the 46 genome parameters stay
// at Ind_O) drives the firmware in the world of `--servo-law identified --imu cm730 --noise on`.
// The stock balance falls there in every seed within 7 s. With this file: forward, backward,
// sideways and turning both ways hold (do not fall) at every step from 5 ms to 0.25 ms (only
// forward and the turns go the commanded way), and the forward walk holds on robots that
// differ from the model (figures: firmware/src/walk/README.md and tests/bench/RESULTS.md; the
// benchmark covers the steps this test does not).
// It pins the world and walk of issue 20: the seed's 2 cm grass, and the firmware's walk
// defaults of then (firmware/config/seed-walk.json: no compliance feed-forward, no support
// exchange at touchdown, no heading hold) under the file. The faithful default world of
// issue 29 (turf, those on) is walk_compliance_test.cpp's.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include "robot_variants.hpp"
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

/// One walk episode; `state` (if given) gets the motion state at its end.
sim::EpisodeResult walk(sim::WorldOptions options, Walk command, double duration_s,
                        bool tuned = true, fw::MotionState* state = nullptr) {
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
  const sim::EpisodeResult result = sim::run_episode(robot, step, episode);
  if (state != nullptr) *state = controller.motion().state();
  return result;
}

// Forward to 2.5 m in 10 of 10 noisy seeds at the default 2 ms step and at 0.5 ms (the
// benchmark adds 5, 2.5, 1 and 0.25 ms), where the stock balance reaches it in none.
TEST(BalanceIdentified, ForwardReachesTheGoalInTenOfTenSeedsAtTwoAndHalfAMillisecondSteps) {
  for (const std::int64_t step_us : {2000, 500}) {
    int reached = 0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      const sim::EpisodeResult r = walk(identified_world(seed, step_us), {1, 0, 0}, 40.0);
      EXPECT_EQ(r.status, sim::WorldStatus::kRunning) << r.failure_reason;
      EXPECT_FALSE(r.fell) << step_us << " us, seed " << seed << " at " << r.fall_time_s << " s";
      if (!r.fell && r.time_to_goal_s) ++reached;
    }
    std::printf("  %lld us: forward 2.5 m in %d/10 seeds\n", static_cast<long long>(step_us),
                reached);
    EXPECT_EQ(reached, 10) << step_us << " us";
  }
  // The stock balance on the same world: the chatter-tuned gains fall (seed 1, 2 ms).
  const sim::EpisodeResult stock = walk(identified_world(1, 2000), {1, 0, 0}, 40.0, false);
  EXPECT_TRUE(stock.fell);
  EXPECT_LT(stock.fall_time_s, 10.0);
}

// Backward, sideways both ways and turning both ways: 20 s without a fall, still walking at the
// end (seed 1, 2 ms). Only the turns move the commanded way: measured turning left 0.49 rad and
// right 0.18 rad in 20 s. Backward and sideways step but do not go where they are commanded
// (measured: backward ends 0.072 m *forward*, left 0.004 m left, right 0.007 m right; the walk
// README's "sideways does not move sideways"), so for them the test checks no more than that.
TEST(BalanceIdentified, BackwardAndSidewaysTwentySecondsWithoutAFallAndTheTurnsTurn) {
  struct Direction {
    const char* name;
    Walk command;
  };
  for (const Direction d : {Direction{"backward", {-1, 0, 0}}, Direction{"left", {0, 1, 0}},
                            Direction{"right", {0, -1, 0}}, Direction{"turn left", {0, 0, 1}},
                            Direction{"turn right", {0, 0, -1}}}) {
    fw::MotionState state = fw::MotionState::kStand;
    const sim::EpisodeResult r = walk(identified_world(1, 2000), d.command, 20.0, true, &state);
    std::printf("  %s: fell %d x %.4f m y %.4f m turned %.4f rad\n", d.name, r.fell ? 1 : 0,
                r.distance_m, r.lateral_m, r.turned_rad);
    EXPECT_EQ(r.status, sim::WorldStatus::kRunning) << r.failure_reason;
    EXPECT_FALSE(r.fell) << d.name << " at " << r.fall_time_s << " s";
    EXPECT_EQ(state, fw::MotionState::kWalk) << d.name;  // stepping, not standing
    if (d.command.vth > 0) {
      EXPECT_GT(r.turned_rad, 0.35) << d.name;  // measured 0.49
    }
    if (d.command.vth < 0) {
      EXPECT_LT(r.turned_rad, -0.12) << d.name;  // measured -0.18
    }
  }
}

// Robots that differ from the model as real ones do (sim_hal/models/make_variants.py: trunk
// +-10 %, its centre of mass 1 cm off each way, one leg 5 % heavier): forward to 2.5 m in 10 of
// 10 seeds on each, with no fall before the goal (2 ms step).
TEST(BalanceIdentified, ForwardReachesTheGoalOnRobotsThatDifferFromTheModel) {
  test::TempDir tmp;
  int code = -1;
  const std::string out = test::write_robot_variants(tmp.path(), code);
  ASSERT_EQ(code, 0) << out;
  for (const char* name : test::kRobotVariants) {
    const std::filesystem::path urdf = tmp.path() / (std::string(name) + ".urdf");
    auto model = std::make_shared<sim::RobotModel>();
    const Status loaded = sim::RobotModel::load_file(urdf, *model);
    ASSERT_TRUE(loaded) << loaded.message();
    int reached = 0, fell_after = 0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      sim::WorldOptions options = identified_world(seed, 2000);
      options.urdf = urdf;
      options.model = model;
      const sim::EpisodeResult r = walk(options, {1, 0, 0}, 40.0);
      ASSERT_EQ(r.status, sim::WorldStatus::kRunning) << name << ": " << r.failure_reason;
      const bool goal = r.time_to_goal_s && (!r.fell || *r.time_to_goal_s < r.fall_time_s);
      EXPECT_TRUE(goal) << name << ", seed " << seed << (r.fell ? " fell" : " too slow");
      reached += goal ? 1 : 0;
      fell_after += goal && r.fell ? 1 : 0;
    }
    std::printf("  %s: 2.5 m in %d/10 seeds (%d fell after the goal)\n", name, reached, fell_after);
  }
}

}  // namespace
}  // namespace stride
