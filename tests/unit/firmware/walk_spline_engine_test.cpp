// SplineWalkEngine and WalkSelector without physics: walk.engine chooses the engine at a walk's
// start; the states from start to stop; the planned feet follow the command (forward, sideways
// on the outer foot, turning on both feet); joint targets stay continuous when steps end early
// at a touchdown; step() allocates nothing and is deterministic.
#include "stride/firmware/walk/spline_walk_engine.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "counting_allocator.hpp"
#include "stride/firmware/walk/walk_engine.hpp"
#include "stride/firmware/walk/walk_selector.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw {
namespace {

constexpr std::int64_t kPeriodNs = 10'000'000;  // 100 Hz
constexpr int kTicksPerSecond = 100;

struct Rig {
  ParameterStore store;
  AttitudeEstimator attitude{store, 0.01};  // the controller's: updated before each step
  WalkEngine seed{store, ServoTable::defaults(), kPeriodNs, attitude};
  SplineWalkEngine spline{store, ServoTable::defaults(), kPeriodNs, attitude};
  WalkSelector selector{store, seed, spline};
  hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();
  hal::CommandFrame out;
  hal::Tick tick = 0;

  Rig() { EXPECT_TRUE(store.set_now({{"walk.engine", 1}}).is_ok()); }
  void start(double vx, double vy, double w) {
    selector.set_velocity(vx, vy, w);
    selector.start(sensors, out, tick);
  }
  void run(int ticks) {
    for (int i = 0; i < ticks; ++i) {
      store.apply_staged();
      attitude.update(sensors.cm730);
      selector.step(sensors, tick++, out);
    }
  }
};

std::size_t index(const char* name) {
  return *ServoTable::defaults().index_of(name);
}

TEST(WalkSelector, WalkEngineChoosesTheEngineWhenAWalkStarts) {
  Rig rig;
  ASSERT_TRUE(rig.store.set_now({{"walk.engine", 0}}).is_ok());
  rig.start(1, 0, 0);
  EXPECT_EQ(rig.selector.active(), WalkSelector::kSeedZmp);
  EXPECT_EQ(rig.seed.state(), WalkEngine::State::kStarting);
  EXPECT_EQ(rig.spline.state(), SplineWalkEngine::State::kStopped);
  // A change while walking waits for the next start.
  ASSERT_TRUE(rig.store.stage("walk.engine", 1).is_ok());
  rig.run(10);
  EXPECT_EQ(rig.selector.active(), WalkSelector::kSeedZmp);
  rig.start(1, 0, 0);
  EXPECT_EQ(rig.selector.active(), WalkSelector::kSpline);
  EXPECT_EQ(rig.spline.state(), SplineWalkEngine::State::kStarting);
  EXPECT_FALSE(rig.store.check("walk.engine", 2).is_ok());
}

TEST(SplineWalkEngine, RegistersItsParametersAndClosedLoopPartsUnderWalkSpline) {
  ParameterStore store;
  AttitudeEstimator attitude(store, 0.01);
  SplineWalkEngine engine(store, ServoTable::defaults(), kPeriodNs, attitude);
  for (const auto& row : walk::spline_walk_parameter_table()) {
    const auto h = store.find(row.name);
    ASSERT_TRUE(h.has_value()) << row.name;
    EXPECT_EQ(store.value(*h), row.default_value) << row.name;
    EXPECT_LE(row.min, row.default_value) << row.name;
    EXPECT_GE(row.max, row.default_value) << row.name;
  }
  for (const char* name : {"walk.spline.capture.touchdown_load", "walk.spline.balance.heading_gain",
                           "walk.spline.compliance.gain", "walk.spline.balance.ankle_pitch_gain"})
    EXPECT_TRUE(store.find(name).has_value()) << name;
  EXPECT_FALSE(store.find("walk.walk_cycle.step_time").has_value());  // the seed's stay apart
}

TEST(SplineWalkEngine, StartsStepsAndStopsWithTheFeetTogether) {
  Rig rig;
  rig.start(1, 0, 0);
  EXPECT_FALSE(rig.selector.done());
  rig.run(SplineWalkEngine::kStartBlendTime * kTicksPerSecond);
  EXPECT_EQ(rig.spline.state(), SplineWalkEngine::State::kStarting);
  rig.run(1);
  EXPECT_EQ(rig.spline.state(), SplineWalkEngine::State::kWalking);
  rig.run(5 * kTicksPerSecond);
  const int steps = rig.spline.snapshot().step_count;
  const auto& p = rig.spline.parameters();
  EXPECT_NEAR(steps, 5.0 * 2.0 * p.frequency, 2.0);  // no touchdowns: the clock's pace
  EXPECT_GT(rig.spline.snapshot().velocity.x, 0.0);
  rig.selector.request_stop();
  EXPECT_EQ(rig.spline.state(), SplineWalkEngine::State::kStopping);
  rig.run(5 * kTicksPerSecond);
  EXPECT_TRUE(rig.selector.done());
  const auto& s = rig.spline.snapshot();
  const walk::Pose2 rel = walk::relative(s.right_foot, s.left_foot);
  EXPECT_NEAR(rel.x, 0.0, 1e-9);
  EXPECT_NEAR(rel.y, p.foot_distance, 1e-9);
  EXPECT_NEAR(s.left_lift, 0.0, 1e-9);
  EXPECT_NEAR(s.right_lift, 0.0, 1e-9);
  EXPECT_EQ(s.velocity.x, 0.0);
}

TEST(SplineWalkEngine, StopDuringTheStartBlendEndsStopped) {
  Rig rig;
  rig.start(1, 0, 0);
  rig.run(20);
  rig.selector.request_stop();
  EXPECT_TRUE(rig.selector.done());
}

// Walks `seconds` at a command after the start blend and returns the snapshot.
SplineWalkEngine::Snapshot walk_for(Rig& rig, double vx, double vy, double w, double seconds) {
  rig.start(vx, vy, w);
  rig.run(static_cast<int>((SplineWalkEngine::kStartBlendTime + seconds) * kTicksPerSecond));
  return rig.spline.snapshot();
}

TEST(SplineWalkEngine, ThePlannedFeetFollowAForwardCommand) {
  Rig rig;
  const auto s = walk_for(rig, 1, 0, 0, 8.0);
  const auto& p = rig.spline.parameters();
  const double full = p.max_step_forward * 2.0 * p.frequency;
  EXPECT_NEAR(s.velocity.x, full, 1e-9);
  // In place for start_steps, then accelerating: over 8 s at least 6 s at full speed.
  const double mid_x = 0.5 * (s.left_foot.x + s.right_foot.x);
  EXPECT_GT(mid_x, 6.0 * full);
  EXPECT_LT(mid_x, 8.0 * full);
  EXPECT_NEAR(s.left_foot.theta, 0.0, 1e-9);
  EXPECT_EQ(rig.spline.ik_clamped_ticks(), 0u);
}

TEST(SplineWalkEngine, SidewaysTheFeetKeepTheirWidthAndTheOuterFootLeads) {
  Rig rig;
  const auto first = walk_for(rig, 0, -1, 0, 1.0);  // to the right
  const double start_x = 0.5 * (first.left_foot.x + first.right_foot.x);
  rig.run(5 * kTicksPerSecond);
  const auto s = rig.spline.snapshot();
  const auto& p = rig.spline.parameters();
  EXPECT_NEAR(s.velocity.y, -p.max_step_side * p.frequency, 1e-9);
  const double mid_y = 0.5 * (s.left_foot.y + s.right_foot.y);
  EXPECT_LT(mid_y, -3.0 * p.max_step_side * p.frequency);  // >= 3 of 6 s at full speed
  const double width = s.left_foot.y - s.right_foot.y;
  EXPECT_GE(width, p.foot_distance - 1e-9);
  EXPECT_LE(width, p.foot_distance + p.max_step_side + 1e-9);
  EXPECT_NEAR(0.5 * (s.left_foot.x + s.right_foot.x), start_x, 1e-6);  // no drift in x
}

TEST(SplineWalkEngine, TurningInPlaceTurnsBothFeet) {
  Rig rig;
  rig.start(0, 0, 1);
  rig.run(static_cast<int>((SplineWalkEngine::kStartBlendTime + 4.0) * kTicksPerSecond));
  // From here on every step changes its swing foot's yaw, left and right alike.
  double left_turned = 0.0, right_turned = 0.0;
  walk::Pose2 left = rig.spline.snapshot().left_foot, right = rig.spline.snapshot().right_foot;
  for (int i = 0; i < 3 * kTicksPerSecond; ++i) {
    rig.run(1);
    const auto& s = rig.spline.snapshot();
    left_turned += walk::wrap_angle(s.left_foot.theta - left.theta);
    right_turned += walk::wrap_angle(s.right_foot.theta - right.theta);
    left = s.left_foot;
    right = s.right_foot;
  }
  const auto& p = rig.spline.parameters();
  const double expected = 3.0 * p.max_turn * p.frequency;  // 3 s at full turn
  EXPECT_NEAR(left_turned, expected, 0.25 * expected);
  EXPECT_NEAR(right_turned, expected, 0.25 * expected);
  EXPECT_GT(std::abs(rig.spline.snapshot().hips.theta), 0.5 * expected);
}

double largest_target_jump(Rig& rig, int ticks, bool touchdowns) {
  double largest = 0.0;
  std::vector<double> previous(hal::kServoCount);
  for (std::size_t i = 0; i < hal::kServoCount; ++i) previous[i] = rig.out.servos[i].position_rad;
  const std::size_t knees[] = {index("l_knee"), index("r_knee")};
  for (int k = 0; k < ticks; ++k) {
    // Touchdowns: every knee reports load now and then, so steps end early at varied phases.
    for (std::size_t knee : knees)
      rig.sensors.servos[knee].load = touchdowns && (k % 7 == 0 || k % 11 == 0) ? 0.5 : 0.0;
    rig.run(1);
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      largest = std::max(largest, std::abs(rig.out.servos[i].position_rad - previous[i]));
      previous[i] = rig.out.servos[i].position_rad;
    }
  }
  return largest;
}

TEST(SplineWalkEngine, TargetsStayContinuousWhenStepsEndEarlyAtTouchdown) {
  Rig clock, early;
  // The trunk rocking at 1.2 rad/s about x and y: the balance feedback shifts the legs by its
  // largest amount and hands it between them at every step.
  for (Rig* rig : {&clock, &early}) rig->sensors.cm730.gyro_rad_s = {1.2, -1.2, 0.0};
  clock.start(1, 0.5, 0.5);
  early.start(1, 0.5, 0.5);
  const double smooth = largest_target_jump(clock, 10 * kTicksPerSecond, false);
  const double with_touchdowns = largest_target_jump(early, 10 * kTicksPerSecond, true);
  EXPECT_GT(early.spline.touchdown_steps(), 5u);
  EXPECT_EQ(clock.spline.touchdown_steps(), 0u);
  // At 100 Hz the joints move at most a few degrees a tick; an early step end adds no jump.
  EXPECT_LT(smooth, 0.12);
  EXPECT_LT(with_touchdowns, 0.12);
}

TEST(SplineWalkEngine, OutputsGainsForTheLegsAndArmsAndLeavesTheHead) {
  Rig rig;
  rig.out.servos[index("head_yaw")].position_rad = 0.3;
  walk_for(rig, 1, 0, 0, 1.0);
  const auto& p = rig.spline.parameters();
  EXPECT_EQ(rig.out.servos[index("l_knee")].p_gain, std::round(2.54 * p.gain_legs));
  EXPECT_EQ(rig.out.servos[index("r_elbow")].p_gain, std::round(2.54 * p.gain_arms));
  EXPECT_EQ(rig.out.servos[index("head_yaw")].position_rad, 0.3);
  EXPECT_GT(rig.out.servos[index("l_knee")].position_rad, 0.2);  // knees bent
}

TEST(SplineWalkEngine, StepAllocatesNothingAndIsDeterministic) {
  Rig a, b;
  a.start(0.7, -0.3, 0.4);
  b.start(0.7, -0.3, 0.4);
  a.run(150);
  test::start_counting_allocations();
  a.run(400);
  EXPECT_EQ(test::stop_counting_allocations(), 0u);
  b.run(550);
  for (std::size_t i = 0; i < hal::kServoCount; ++i)
    EXPECT_EQ(a.out.servos[i].position_rad, b.out.servos[i].position_rad) << i;
}

}  // namespace
}  // namespace stride::fw
