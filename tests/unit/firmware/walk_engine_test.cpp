// WalkEngine: parameters in the store, state transitions (start blend, initial steps without
// lift, stop request, last step, stopped), outputs (URDF angles, gains), determinism.
#include "stride/firmware/walk/walk_engine.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace stride::fw {
namespace {

constexpr std::int64_t kPeriodNs = 10'000'000;  // 100 Hz

struct Rig {
  ParameterStore store;
  AttitudeEstimator attitude{store, 0.01};  // the controller's: updated before each step
  WalkEngine engine{store, ServoTable::defaults(), kPeriodNs, attitude};
  hal::SensorFrame sensors;
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

std::size_t index(const char* name) {
  return *ServoTable::defaults().index_of(name);
}

TEST(WalkEngine, RegistersTheParametersWithIndODefaults) {
  ParameterStore store;
  AttitudeEstimator attitude(store, 0.01);
  WalkEngine engine{store, ServoTable::defaults(), kPeriodNs, attitude};
  EXPECT_EQ(store.list("walk.").size() - store.list("walk.balance.").size() -
                store.list("walk.compliance.").size() - store.list("walk.capture.").size(),
            walk::kWalkParameterCount);
  int genome = 0;
  for (const auto& row : walk::walk_parameter_table()) {
    const auto h = store.find(row.name);
    ASSERT_TRUE(h.has_value()) << row.name;
    EXPECT_EQ(store.value(*h), row.default_value);
    EXPECT_LT(row.min, row.max);
    if (row.table_e_index > 0) {
      ++genome;
      EXPECT_EQ(row.table_e_index, genome) << row.name;  // Table E order
      if (row.default_value != 0.0) {
        // About +-50 % of Ind_O.
        const double half = 0.5 * std::abs(row.default_value);
        EXPECT_LE(row.max - row.default_value, half + 1e-12) << row.name;
        EXPECT_LE(row.default_value - row.min, half + 1e-12) << row.name;
        EXPECT_GE(row.max - row.min, half) << row.name;
      }
    }
  }
  EXPECT_EQ(genome, 46);
  double v = 0.0;
  ASSERT_TRUE(store.get("walk.walk_cycle.step_time", v).is_ok());
  EXPECT_EQ(v, 0.85);
  ASSERT_TRUE(store.get("walk.stance.body_height", v).is_ok());
  EXPECT_EQ(v, 0.60);
  EXPECT_FALSE(store.check("walk.walk_cycle.zmp_time", 0.7).is_ok());
}

TEST(WalkEngine, StateTransitionsFromStartToStop) {
  Rig rig;
  EXPECT_TRUE(rig.engine.done());
  rig.engine.set_velocity(1.0, 0.0, 0.0);
  rig.engine.start(rig.sensors, rig.out, rig.tick);
  EXPECT_EQ(rig.engine.state(), WalkEngine::State::kStarting);
  EXPECT_FALSE(rig.engine.done());
  rig.run(100);  // 1 s blend
  EXPECT_EQ(rig.engine.state(), WalkEngine::State::kStarting);
  rig.run(1);
  EXPECT_EQ(rig.engine.state(), WalkEngine::State::kWalking);
  EXPECT_EQ(rig.engine.snapshot().step_count, 1);
  // The first two steps: zero velocity, no lift.
  double max_lift = 0.0;
  for (int i = 0; i < 169; ++i) {
    rig.run(1);
    max_lift =
        std::max({max_lift, rig.engine.snapshot().left_lift, rig.engine.snapshot().right_lift});
    EXPECT_EQ(rig.engine.snapshot().velocity.x, 0.0);
  }
  EXPECT_EQ(rig.engine.snapshot().step_count, 2);
  EXPECT_EQ(max_lift, 0.0);
  rig.run(85);  // third step: moving, lifting
  EXPECT_EQ(rig.engine.snapshot().step_count, 3);
  EXPECT_GT(rig.engine.snapshot().velocity.x, 0.0);
  rig.run(400);
  const double x_walked = rig.engine.snapshot().torso.x;
  EXPECT_GT(x_walked, 0.3);
  rig.engine.request_stop();
  EXPECT_EQ(rig.engine.state(), WalkEngine::State::kStopRequest);
  EXPECT_FALSE(rig.engine.done());
  int ticks = 0;
  bool saw_last_step = false;
  while (!rig.engine.done() && ticks < 400) {
    rig.run(1);
    ++ticks;
    saw_last_step = saw_last_step || rig.engine.state() == WalkEngine::State::kLastStep;
  }
  EXPECT_TRUE(saw_last_step);
  EXPECT_TRUE(rig.engine.done());
  EXPECT_LE(ticks, 2 * 85 + 1);  // the current step, then the last one
  // Stopped: both feet down, side by side at the nominal width, torso between them.
  const auto& s = rig.engine.snapshot();
  EXPECT_EQ(s.left_lift, 0.0);
  EXPECT_EQ(s.right_lift, 0.0);
  const walk::Pose2 rel = walk::relative(s.right_foot, s.left_foot);
  EXPECT_NEAR(rel.x, 0.0, 1e-9);
  EXPECT_NEAR(rel.y, 0.21, 1e-9);
  EXPECT_NEAR(walk::relative(s.left_foot, s.torso).x, 0.072, 1e-9);
  // Stays stopped and still.
  const auto before = rig.out;
  rig.run(50);
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    EXPECT_EQ(before.servos[i].position_rad, rig.out.servos[i].position_rad);
  }
}

TEST(WalkEngine, StopDuringTheStartBlendEndsStopped) {
  Rig rig;
  rig.engine.start(rig.sensors, rig.out, rig.tick);
  rig.run(10);
  rig.engine.request_stop();
  rig.run(100);
  EXPECT_TRUE(rig.engine.done());
}

TEST(WalkEngine, StartBlendsFromTheLastCommands) {
  Rig rig;
  for (auto& s : rig.out.servos) {
    s.position_rad = 0.0;
    s.torque_enable = true;
  }
  rig.engine.start(rig.sensors, rig.out, 500);
  rig.tick = 500;
  rig.run(1);
  EXPECT_EQ(rig.out.servos[index("l_knee")].position_rad, 0.0);  // blend weight 0 at t = 0
  rig.run(99);
  const double knee_end = rig.out.servos[index("l_knee")].position_rad;
  EXPECT_GT(knee_end, 0.3);  // body height 0.60 bends the knees
  EXPECT_EQ(rig.out.tick, 599);
}

TEST(WalkEngine, OutputsUrdfAnglesGainsAndFullSpeed) {
  Rig rig;
  rig.engine.start(rig.sensors, rig.out, 0);
  rig.run(120);
  const auto& o = rig.out.servos;
  // Arm pitch 1.570 (NUbots) -> 1.570 - pi/2 (URDF).
  EXPECT_NEAR(o[index("l_shoulder_pitch")].position_rad, 1.570 - std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(o[index("r_elbow")].position_rad, -0.523, 1e-12);
  // Shoulder-roll floor outward: left positive, right negative (5 deg + 19.5 deg here).
  EXPECT_GT(o[index("l_shoulder_roll")].position_rad, 0.08);
  EXPECT_LT(o[index("r_shoulder_roll")].position_rad, -0.08);
  EXPECT_EQ(o[index("l_knee")].p_gain, 38.0);   // round(2.54 * 15)
  EXPECT_EQ(o[index("r_elbow")].p_gain, 25.0);  // round(2.54 * 10)
  EXPECT_EQ(o[index("l_knee")].moving_speed_rad_s, 0.0);
  EXPECT_TRUE(o[index("l_knee")].torque_enable);
  EXPECT_FALSE(o[index("head_yaw")].torque_enable);  // untouched
  // Knees bent alike, hip pitch forward (negative) with the forward body tilt.
  EXPECT_GT(o[index("r_knee")].position_rad, 0.3);
  EXPECT_LT(o[index("r_hip_pitch")].position_rad, 0.0);
}

TEST(WalkEngine, ParameterChangesApplyAtTheNextStep) {
  Rig rig;
  rig.engine.start(rig.sensors, rig.out, 0);
  rig.run(110);
  ASSERT_TRUE(rig.store.stage("walk.walk_cycle.step_time", 0.6).is_ok());
  rig.run(1);
  EXPECT_EQ(rig.engine.parameters().step_time, 0.85);
  rig.run(85);
  EXPECT_EQ(rig.engine.parameters().step_time, 0.6);
}

TEST(WalkEngine, BalanceFeedbackShiftsTheSupportLegAndZeroGainsAreOpenLoop) {
  Rig still, shaken, fed_back;
  for (Rig* r : {&still, &shaken, &fed_back}) r->engine.start(r->sensors, r->out, 0);
  shaken.sensors.cm730.gyro_rad_s = {0.5, 0.8, 0.0};
  fed_back.sensors.cm730.gyro_rad_s = {0.5, 0.8, 0.0};
  const std::vector<ParamWrite> open_loop{{"walk.balance.ankle_pitch_gain", 0.0},
                                          {"walk.balance.ankle_roll_gain", 0.0},
                                          {"walk.balance.hip_pitch_gain", 0.0},
                                          {"walk.balance.hip_roll_gain", 0.0}};
  // The gyro feedback alone: the compliance feed-forward (on by default) would add the
  // deflection of whatever the goals are, shifted or not.
  for (Rig* r : {&still, &shaken, &fed_back})
    ASSERT_TRUE(r->store.set_now({{"walk.compliance.gain", 0.0}}).is_ok());
  ASSERT_TRUE(still.store.set_now(open_loop).is_ok());
  ASSERT_TRUE(shaken.store.set_now(open_loop).is_ok());
  ASSERT_TRUE(fed_back.store
                  .set_now({{"walk.balance.ankle_pitch_gain", 0.2},
                            {"walk.balance.ankle_roll_gain", 0.1},
                            {"walk.balance.hip_pitch_gain", 0.0},
                            {"walk.balance.hip_roll_gain", 0.1},
                            {"walk.balance.deadband", 0.0},
                            {"walk.balance.pitch_angle_gain", 0.0},
                            {"walk.balance.roll_angle_gain", 0.0}})
                  .is_ok());
  still.run(150);  // first step: the left leg swings, the right supports
  shaken.run(150);
  fed_back.run(150);
  const std::size_t ankle = index("r_ankle_pitch");
  const std::size_t roll = index("r_ankle_roll");
  EXPECT_EQ(shaken.out.servos[ankle].position_rad, still.out.servos[ankle].position_rad);
  EXPECT_NEAR(fed_back.out.servos[ankle].position_rad - still.out.servos[ankle].position_rad,
              0.2 * 0.8, 1e-6);
  EXPECT_NEAR(fed_back.out.servos[roll].position_rad - still.out.servos[roll].position_rad,
              0.1 * 0.5, 1e-6);
}

TEST(WalkEngine, IsDeterministic) {
  Rig a, b;
  for (Rig* r : {&a, &b}) {
    r->engine.set_velocity(0.7, -0.4, 0.3);
    r->engine.start(r->sensors, r->out, 0);
  }
  for (int i = 0; i < 1500; ++i) {
    a.run(1);
    b.run(1);
    for (std::size_t k = 0; k < hal::kServoCount; ++k) {
      ASSERT_EQ(a.out.servos[k].position_rad, b.out.servos[k].position_rad);
      ASSERT_TRUE(std::isfinite(a.out.servos[k].position_rad));
    }
  }
}

TEST(WalkEngine, TorsoSwaysTowardsTheSupportFoot) {
  Rig rig;
  // The full sway from the first step (the default ramps it in over 1.5 steps).
  ASSERT_TRUE(rig.store.set_now({{"walk.balance.start_sway_steps", 0.0}}).is_ok());
  rig.engine.start(rig.sensors, rig.out, 0);
  rig.run(101);  // first step begins
  const bool left_swings = rig.engine.snapshot().swing == walk::Foot::kLeft;
  double extreme = 0.0;
  for (int i = 0; i < 84; ++i) {
    rig.run(1);
    const double y = rig.engine.snapshot().torso.y;
    extreme = left_swings ? std::min(extreme, y) : std::max(extreme, y);
  }
  EXPECT_GT(std::abs(extreme), 0.02);  // sways towards the support side
}

}  // namespace
}  // namespace stride::fw
