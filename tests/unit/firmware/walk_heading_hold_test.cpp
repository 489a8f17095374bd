// HeadingHold (walk.balance.heading_*): bias learned while the start blend stands, the
// integrated yaw fed back into each step's turn, off with the gains at 0, cleared while a turn
// is commanded; in the WalkEngine the correction turns the planned footsteps. Also the wide
// store ranges of the omnidirectional walk (walk_parameter_wide_ranges()).
#include "stride/firmware/walk/heading_hold.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "stride/firmware/walk/walk_engine.hpp"

#include "fed_heading_hold.hpp"

namespace stride::fw {
namespace {

constexpr double kPeriod = 0.01;
constexpr std::int64_t kPeriodNs = 10'000'000;

// The hold is on by default (walk.balance.heading_gain 0.5 since issue 29); these tests set
// their own gain and limit.
const std::vector<ParamWrite> kOn{{"walk.balance.heading_gain", 0.3},
                                  {"walk.balance.heading_max_correction", 0.1}};

hal::Cm730State gyro(double gx, double gz) {
  hal::Cm730State s;
  s.gyro_rad_s = {gx, 0.0, gz};
  return s;
}

/// A heading hold fed as the walk feeds it (fed_heading_hold.hpp). (The readings of gyro() have no
/// specific force: the estimate stays upright and the yaw rate is g_z.)
struct Hold : test::FedHeadingHold {
  explicit Hold(ParameterStore& store) : FedHeadingHold(store, kPeriod) {}
};

TEST(HeadingHold, IsOnByDefaultAndGainZeroIsOff) {
  for (const bool off : {false, true}) {
    ParameterStore store;
    Hold fed(store);
    walk::HeadingHold& hold = fed.hold;
    // The faithful world's default: on at 0.5 rad/step per rad (issue 29 point 6).
    if (off) {
      ASSERT_TRUE(store.set_now({{"walk.balance.heading_gain", 0.0}}).is_ok());
    }
    fed.update(gyro(0.0, 0.0), true, true);
    for (int i = 0; i < 100; ++i) fed.update(gyro(0.0, 0.5), false, true);
    EXPECT_NEAR(hold.heading_error(), 0.5, 1e-9);  // it measures either way
    if (off) {
      EXPECT_EQ(hold.begin_step(), 0.0);
    } else {
      EXPECT_LT(hold.begin_step(), -0.05);  // turns back right
    }
  }
}

TEST(HeadingHold, LearnsTheBiasWhileStandingAndFeedsBackTheTwoStepMeanError) {
  ParameterStore store;
  Hold fed(store);
  walk::HeadingHold& hold = fed.hold;
  ASSERT_TRUE(store.set_now(kOn).is_ok());
  hold.reset();
  for (int i = 0; i < 100; ++i) fed.update(gyro(0.0, 0.02), true, true);
  EXPECT_NEAR(hold.bias(), 0.02, 1e-12);
  // The bias alone integrates to nothing.
  for (int i = 0; i < 100; ++i) fed.update(gyro(0.0, 0.02), false, true);
  EXPECT_NEAR(hold.heading_error(), 0.0, 1e-12);
  EXPECT_NEAR(hold.begin_step(), 0.0, 1e-12);
  // A step of 0.1 rad/s above the bias for 1 s: 0.1 rad to the left, mean 0.0505 over the step.
  for (int i = 0; i < 100; ++i) fed.update(gyro(0.0, 0.12), false, true);
  EXPECT_NEAR(hold.heading_error(), 0.1, 1e-9);
  EXPECT_NEAR(hold.begin_step(), -0.3 * 0.5 * (0.0 + 0.0505), 1e-9);
  // A still step: the pair mean is (0.0505 + 0.1) / 2, then 0.1; corrected to the right.
  for (int i = 0; i < 100; ++i) fed.update(gyro(0.0, 0.02), false, true);
  EXPECT_NEAR(hold.begin_step(), -0.3 * 0.5 * (0.0505 + 0.1), 1e-9);
  for (int i = 0; i < 100; ++i) fed.update(gyro(0.0, 0.02), false, true);
  EXPECT_NEAR(hold.begin_step(), -0.3 * 0.1, 1e-9);
  EXPECT_NEAR(hold.step_pair_mean(), 0.1, 1e-9);
}

TEST(HeadingHold, AYawSwingOfOneStepPairAveragesOut) {
  // The torso yaws +-4 deg once per step pair (0.85 s steps): the step starts catch the swing
  // at its ends, the two-step mean does not.
  ParameterStore store;
  Hold fed(store);
  walk::HeadingHold& hold = fed.hold;
  ASSERT_TRUE(store.set_now(kOn).is_ok());
  fed.update(gyro(0.0, 0.0), true, true);
  const double amplitude = 4.0 * std::numbers::pi / 180.0;
  const double omega = std::numbers::pi / 0.85;  // one period per two steps
  double worst = 0.0;
  for (int step = 0; step < 20; ++step) {
    for (int i = 0; i < 85; ++i) {
      const double t = (step * 85 + i) * kPeriod;
      fed.update(gyro(0.0, amplitude * omega * std::cos(omega * t)), false, true);
    }
    const double c = hold.begin_step();
    if (step >= 2) worst = std::max(worst, std::abs(c));
  }
  EXPECT_LT(worst, 1e-3);  // the instantaneous error at the step starts: +-0.07 rad
}

TEST(HeadingHold, ProjectsTheGyroOntoTheWorldsVerticalWithTheAttitude) {
  ParameterStore store;
  Hold fed(store);
  ASSERT_TRUE(store.set_now(kOn).is_ok());
  // The torso pitched forward by 0.3 rad (the accelerometer says so): a roll rate about the
  // torso's x is partly a yaw rate, -sin(0.3) g_x.
  hal::Cm730State pitched = gyro(0.0, 0.0);
  pitched.accel_mps2 = {-9.81 * std::sin(0.3), 0.0, 9.81 * std::cos(0.3)};
  fed.update(pitched, true, true);
  pitched.gyro_rad_s = {0.2, 0.0, 0.0};
  for (int i = 0; i < 100; ++i) fed.update(pitched, false, true);
  EXPECT_NEAR(fed.hold.heading_error(), -std::sin(0.3) * 0.2, 2e-3);
}

TEST(HeadingHold, ClampsAndIsOffWithZeroGainsAndWhileTurning) {
  ParameterStore store;
  Hold fed(store);
  walk::HeadingHold& hold = fed.hold;
  ASSERT_TRUE(store.set_now(kOn).is_ok());
  fed.update(gyro(0.0, 0.0), true, true);
  for (int i = 0; i < 100; ++i) fed.update(gyro(0.0, 1.0), false, true);
  EXPECT_NEAR(hold.heading_error(), 1.0, 1e-9);
  EXPECT_NEAR(hold.begin_step(), -0.1, 1e-12);  // heading_max_correction
  ASSERT_TRUE(store.set_now({{"walk.balance.heading_gain", 0.0}}).is_ok());
  for (int i = 0; i < 100; ++i) fed.update(gyro(0.0, 0.0), false, true);
  EXPECT_EQ(hold.begin_step(), 0.0);
  ASSERT_TRUE(store
                  .set_now({{"walk.balance.heading_gain", 0.3},
                            {"walk.balance.heading_rate_gain", 0.1},
                            {"walk.balance.heading_max_correction", 0.5}})
                  .is_ok());
  // Error 1 rad for two steps, and the rate term sees the filtered yaw rate (0 now).
  for (int i = 0; i < 100; ++i) fed.update(gyro(0.0, 0.0), false, true);
  EXPECT_NEAR(hold.begin_step(), -0.3, 0.01);
  // The rate term: turning at 1 rad/s for a second with a 0.5 s filter reads ~0.86 rad/s.
  for (int i = 0; i < 100; ++i) fed.update(gyro(0.0, 1.0), false, true);
  EXPECT_LT(hold.begin_step(), -0.3 * 1.25 - 0.07);
  // A commanded turn clears the error: the new heading is held once the turn ends.
  fed.update(gyro(0.0, 1.0), false, false);
  EXPECT_EQ(hold.heading_error(), 0.0);
  EXPECT_EQ(hold.begin_step(), 0.0);
}

/// The torso still, pitched forward by the walk's body tilt (Ind_O's 0.174 rad).
hal::SensorFrame standing_still() {
  hal::SensorFrame f;
  f.cm730.accel_mps2 = {-9.81 * std::sin(0.174), 0.0, 9.81 * std::cos(0.174)};
  return f;
}

struct Rig {
  ParameterStore store;
  AttitudeEstimator attitude{store, kPeriod};  // the controller's: updated before each step
  WalkEngine engine{store, ServoTable::defaults(), kPeriodNs, attitude};
  hal::SensorFrame sensors = standing_still();
  hal::CommandFrame out;
  hal::Tick tick = 0;
  void run(int ticks) {
    for (int i = 0; i < ticks; ++i) {
      store.apply_staged();
      attitude.update(sensors.cm730);
      engine.step(sensors, tick++, out);
    }
  }
};

double foot_yaw_difference(const WalkEngine::Snapshot& s) {
  return s.left_foot.theta + s.right_foot.theta;
}

TEST(WalkHeadingHold, AYawToTheLeftTurnsTheStepsToTheRightAndGainZeroIsOpenLoop) {
  Rig still, yawing, open_loop;  // open_loop: heading_gain 0
  ASSERT_TRUE(still.store.set_now(kOn).is_ok());
  ASSERT_TRUE(yawing.store.set_now(kOn).is_ok());
  ASSERT_TRUE(open_loop.store.set_now({{"walk.balance.heading_gain", 0.0}}).is_ok());
  for (Rig* r : {&still, &yawing, &open_loop}) {
    r->engine.set_velocity(1.0, 0.0, 0.0);
    r->engine.start(r->sensors, r->out, 0);
    r->run(100);  // the start blend: gyro 0, bias 0
  }
  // From now on the torso yaws left at 0.05 rad/s (as if the floor turned the robot).
  yawing.sensors.cm730.gyro_rad_s = {0.0, 0.0, 0.05};
  open_loop.sensors.cm730.gyro_rad_s = {0.0, 0.0, 0.05};
  for (Rig* r : {&still, &yawing, &open_loop}) r->run(1000);  // ten seconds, about 11 steps
  EXPECT_EQ(still.engine.snapshot().heading_correction, 0.0);
  EXPECT_EQ(open_loop.engine.snapshot().heading_correction, 0.0);
  EXPECT_LT(yawing.engine.snapshot().heading_correction, -0.01);
  // 10 s of yaw (the first walking tick still counts into the bias: 0.05 / 101 rad/s), about
  // the world's vertical: the torso is pitched by 0.174 rad.
  EXPECT_NEAR(yawing.engine.snapshot().heading_error,
              9.99 * 0.05 * std::cos(0.174) * (1.0 - 1.0 / 101.0), 1e-3);
  // The planned feet turn right (negative yaw); without the hold they do not turn at all.
  EXPECT_LT(foot_yaw_difference(yawing.engine.snapshot()), -0.05);
  EXPECT_NEAR(foot_yaw_difference(open_loop.engine.snapshot()), 0.0, 1e-12);
  EXPECT_NEAR(foot_yaw_difference(still.engine.snapshot()), 0.0, 1e-12);
  const std::size_t hip_yaw = *ServoTable::defaults().index_of("l_hip_yaw");
  EXPECT_EQ(open_loop.out.servos[hip_yaw].position_rad, still.out.servos[hip_yaw].position_rad);
}

TEST(WalkParameters, WideRangesContainTheSeedBoundsAndTheStoreAcceptsThem) {
  ParameterStore store;
  AttitudeEstimator attitude(store, kPeriod);
  WalkEngine engine(store, ServoTable::defaults(), kPeriodNs, attitude);
  int widened = 0;
  for (const auto& row : walk::walk_parameter_table()) {
    const walk::WalkParameterRange range = walk::walk_parameter_store_range(row);
    EXPECT_LE(range.min, row.min) << row.name;
    EXPECT_GE(range.max, row.max) << row.name;
    EXPECT_TRUE(store.check(std::string(row.name), range.min).is_ok()) << row.name;
    EXPECT_TRUE(store.check(std::string(row.name), range.max).is_ok()) << row.name;
    if (range.min < row.min || range.max > row.max) ++widened;
  }
  EXPECT_EQ(widened, static_cast<int>(walk::walk_parameter_wide_ranges().size()));
  // Sideways up to 0.25 m/step (the seed's bounds stop at 0.015).
  EXPECT_TRUE(store.check("walk.walk_cycle.velocity.limits.y_max", 0.25).is_ok());
  EXPECT_FALSE(store.check("walk.walk_cycle.velocity.limits.y_max", 0.26).is_ok());
  // A step pair's turn up to the hip yaw servos' +-0.8 rad each, steps down to 0.35 s.
  EXPECT_TRUE(store.check("walk.walk_cycle.step.limits.angle_max", 1.6).is_ok());
  EXPECT_FALSE(store.check("walk.walk_cycle.step.limits.angle_max", 1.61).is_ok());
  EXPECT_TRUE(store.check("walk.walk_cycle.step_time", 0.35).is_ok());
  EXPECT_FALSE(store.check("walk.walk_cycle.step_time", 0.34).is_ok());
  // The defaults stay Ind_O.
  EXPECT_EQ(store.spec(*store.find("walk.walk_cycle.step_time")).default_value, 0.85);
  EXPECT_EQ(store.spec(*store.find("walk.walk_cycle.step.limits.angle_max")).default_value, 0.262);
}

}  // namespace
}  // namespace stride::fw
