// CaptureStep: its footstep and timing feedback off by default (gains 0), its support exchange
// at touchdown on (since issue 29); the walk's own periodic rocking is learned and not fed back;
// a tilt beyond it moves the next footstep towards where the robot falls and changes the step
// timing the right way, in the class and inside the walk engine; allocation-free.
#include "stride/firmware/walk/capture_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "counting_allocator.hpp"
#include "stride/firmware/walk/walk_engine.hpp"

namespace stride::fw::walk {
namespace {

constexpr double kPeriod = 0.01;
constexpr double kStepTime = 0.5;

hal::Cm730State imu_at(double roll, double pitch, double roll_rate, double pitch_rate) {
  hal::Cm730State imu;
  imu.accel_mps2 = {-9.81 * std::sin(pitch), 9.81 * std::sin(roll) * std::cos(pitch),
                    9.81 * std::cos(roll) * std::cos(pitch)};
  imu.gyro_rad_s = {roll_rate, pitch_rate, 0.0};
  return imu;
}

struct Rig {
  ParameterStore store;
  AttitudeEstimator attitude{store, kPeriod};  // updated before the capture step, as in the walk
  CaptureStep capture{store, kPeriod};
  double time = 0.0;
  void set(const char* name, double value) { ASSERT_TRUE(store.set_now({{name, value}}).is_ok()); }
  /// Walks `seconds` with the trunk rolling +-amplitude once per step pair, plus `extra` roll.
  void walk(double seconds, double amplitude, double extra = 0.0) {
    const double omega = std::numbers::pi / kStepTime;  // one roll cycle per step pair
    for (double end = time + seconds; time < end - 1e-9; time += kPeriod) {
      const double pair_phase = std::fmod(time, 2.0 * kStepTime) / (2.0 * kStepTime);
      const double roll = amplitude * std::sin(omega * time) + extra;
      attitude.update(imu_at(roll, 0.17, amplitude * omega * std::cos(omega * time), 0.0));
      capture.update(attitude, pair_phase, kStepTime, true, false);
    }
  }
  void stand(double seconds) {
    for (double end = time + seconds; time < end - 1e-9; time += kPeriod) {
      attitude.update(imu_at(0.0, 0.17, 0.0, 0.0));
      capture.update(attitude, 0.0, kStepTime, false, true);
    }
  }
};

TEST(WalkCaptureStep, OffByDefault) {
  Rig rig;
  rig.stand(1.0);
  rig.walk(2.0, 0.05, 0.1);
  EXPECT_FALSE(rig.capture.footstep_enabled());
  EXPECT_FALSE(rig.capture.timing_enabled());
  EXPECT_EQ(rig.capture.step_offset_x(), 0.0);
  EXPECT_EQ(rig.capture.step_offset_y(), 0.0);
  EXPECT_EQ(rig.capture.phase_rate(true), 1.0);
}

TEST(WalkCaptureStep, TheWalksOwnRockingIsLearnedAndNotFedBack) {
  Rig rig;
  rig.stand(1.0);
  double early = 0.0;
  for (int i = 0; i < 10; ++i) {
    rig.walk(0.1, 0.05);
    early = std::max(early, std::abs(rig.capture.deviation_y()));
  }
  rig.walk(20.0, 0.05);  // learning
  double late = 0.0;
  for (int i = 0; i < 20; ++i) {
    rig.walk(0.1, 0.05);
    late = std::max(late, std::abs(rig.capture.deviation_y()));
  }
  EXPECT_GT(early, 0.004);  // before learning, the rocking looks like a deviation
  EXPECT_LT(late, 0.25 * early + 1e-3);
}

TEST(WalkCaptureStep, ATiltMovesTheFootstepAndTheTimingTowardsTheFall) {
  Rig rig;
  rig.set("walk.capture.step_gain_y", 1.0);
  rig.set("walk.capture.step_gain_x", 1.0);
  rig.set("walk.capture.timing_gain", 10.0);
  // The attitude's time constant the capture step's own tilt filter had before issue 55 (the
  // default, 0.84 s, follows a 0.2 s tilt to about 0.6 of it).
  rig.set("walk.balance.tilt_filter_time", 0.3);
  rig.stand(1.0);
  rig.walk(20.0, 0.05);
  EXPECT_LT(std::abs(rig.capture.step_offset_y()), 0.003);
  // The trunk rolls 0.05 rad more to its right (positive roll about x tips the top towards -y):
  // the capture point leaves to the right, the next footstep moves right.
  rig.walk(0.2, 0.05, 0.05);
  EXPECT_LT(rig.capture.deviation_y(), -0.01);
  EXPECT_LT(rig.capture.step_offset_y(), -0.01);
  EXPECT_GE(rig.capture.step_offset_y(), -0.04);  // walk.capture.max_step_y
  // The right foot, swinging, lands sooner; the left one later.
  EXPECT_GT(rig.capture.phase_rate(false), 1.0);
  EXPECT_LT(rig.capture.phase_rate(true), 1.0);
  EXPECT_GE(rig.capture.phase_rate(true), 0.7);  // walk.capture.max_timing 0.3
}

TEST(WalkCaptureStep, TouchdownNeedsALateEnoughPhaseAndLoad) {
  Rig rig;
  EXPECT_TRUE(rig.capture.touchdown(0.95, 0.9));  // on by default (load 0.08, phase 0.7)
  EXPECT_FALSE(rig.capture.touchdown(0.65, 0.9));
  rig.set("walk.capture.touchdown_load", 0.0);
  EXPECT_FALSE(rig.capture.touchdown(0.95, 0.9));  // load 0: off
  rig.set("walk.capture.touchdown_load", 0.2);
  rig.set("walk.capture.touchdown_phase", 0.9);
  EXPECT_FALSE(rig.capture.touchdown(0.8, 0.9));   // before walk.capture.touchdown_phase 0.9
  EXPECT_FALSE(rig.capture.touchdown(0.95, 0.1));  // no weight on the foot yet
  EXPECT_TRUE(rig.capture.touchdown(0.95, -0.3));  // either sign of load
}

/// Steps a walk engine for `seconds` with the knees reporting `knee_load`; returns the steps.
int steps_taken(double touchdown_load, double knee_load, double seconds) {
  ParameterStore store;
  AttitudeEstimator attitude(store, 0.01);
  WalkEngine engine(store, ServoTable::defaults(), 10'000'000, attitude);
  EXPECT_TRUE(store
                  .set_now({{"walk.capture.touchdown_load", touchdown_load},
                            {"walk.capture.touchdown_phase", 0.9}})
                  .is_ok());
  hal::SensorFrame sensors;
  sensors.cm730.accel_mps2 = {0.0, 0.0, 9.81};
  for (auto& servo : sensors.servos) servo.load = knee_load;
  hal::CommandFrame out{};
  engine.set_velocity(1.0, 0.0, 0.0);
  engine.start(sensors, out, 0);
  const int ticks = static_cast<int>(seconds / 0.01);
  for (int t = 0; t < ticks; ++t) {
    attitude.update(sensors.cm730);
    engine.step(sensors, t, out);
  }
  return engine.snapshot().step_count;
}

TEST(WalkCaptureStep, ALandedSwingFootEndsItsStepEarly) {
  // Ind_O's 0.85 s steps: 1 s start blend, then 9 s walking is 11 steps by the clock.
  const int by_clock = steps_taken(0.0, 0.5, 10.0);
  EXPECT_EQ(steps_taken(0.3, 0.1, 10.0), by_clock);  // no touchdown seen
  // A load from the start of the late window: the steps after the first two (no lift) end at
  // phase 0.9, about 10 % sooner.
  const int early = steps_taken(0.3, 0.5, 10.0);
  EXPECT_GT(early, by_clock);
  EXPECT_LE(early, by_clock + 2);
}

/// A walk engine walking in place 12 s with the trunk upright, then (from `disturb_s`) rolled
/// `roll` rad to its right, as the IMU reports it; per step, the feet at the step's last tick
/// and the tick the step began.
struct EngineWalk {
  std::vector<WalkEngine::Snapshot> step_ends;
  std::vector<hal::Tick> step_starts;
  double max_phase_rate = 1.0, min_phase_rate = 1.0;
};

EngineWalk walk_engine(const std::vector<ParamWrite>& gains, double disturb_s, double roll) {
  ParameterStore store;
  AttitudeEstimator attitude(store, 0.01);
  WalkEngine engine(store, ServoTable::defaults(), 10'000'000, attitude);
  EXPECT_TRUE(store.set_now(gains).is_ok());
  hal::SensorFrame sensors;
  hal::CommandFrame out{};
  engine.set_velocity(0.0, 0.0, 0.0);
  sensors.cm730 = imu_at(0.0, 0.0, 0.0, 0.0);
  engine.start(sensors, out, 0);
  EngineWalk walk;
  WalkEngine::Snapshot last;
  for (hal::Tick tick = 0; tick < 1200; ++tick) {
    sensors.cm730 = imu_at(tick * kPeriod >= disturb_s ? roll : 0.0, 0.0, 0.0, 0.0);
    attitude.update(sensors.cm730);
    engine.step(sensors, tick, out);
    const WalkEngine::Snapshot& now = engine.snapshot();
    if (now.step_count != last.step_count) {
      if (last.step_count > 0) walk.step_ends.push_back(last);
      walk.step_starts.push_back(tick);
    }
    walk.max_phase_rate = std::max(walk.max_phase_rate, now.phase_rate);
    walk.min_phase_rate = std::min(walk.min_phase_rate, now.phase_rate);
    last = now;
  }
  return walk;
}

/// The first step that began after `s` seconds.
std::size_t first_step_after(const EngineWalk& walk, double s) {
  std::size_t i = 0;
  while (i < walk.step_starts.size() && walk.step_starts[i] * kPeriod < s) ++i;
  return i;
}

// Inside the walk engine: the trunk rolls 0.05 rad to its right at 8 s, beyond the rocking the
// capture step has learned; the next right footstep lands further right (the footstep feedback)
// and the steps' timing changes (the timing feedback). With the gains at 0 (the default) the
// same disturbance changes nothing.
TEST(WalkCaptureStep, InTheWalkEngineALateralTiltMovesTheNextFootstep) {
  // The attitude's time constant the capture step's own tilt filter had before issue 55.
  const std::vector<ParamWrite> footstep{{"walk.capture.step_gain_y", 1.0},
                                         {"walk.balance.tilt_filter_time", 0.3}};
  const EngineWalk calm = walk_engine(footstep, 1e9, 0.0);
  const EngineWalk tilted = walk_engine(footstep, 8.0, 0.05);
  const EngineWalk off = walk_engine({{"walk.balance.tilt_filter_time", 0.3}}, 8.0, 0.05);
  ASSERT_EQ(tilted.step_starts, calm.step_starts);  // the timing feedback is off
  ASSERT_EQ(off.step_ends.size(), calm.step_ends.size());
  const std::size_t first = first_step_after(calm, 8.0);
  ASSERT_LT(first + 2, calm.step_ends.size());
  double right_shift = 0.0;
  for (std::size_t i = 0; i < calm.step_ends.size(); ++i) {
    const double left = tilted.step_ends[i].left_foot.y - calm.step_ends[i].left_foot.y;
    const double right = tilted.step_ends[i].right_foot.y - calm.step_ends[i].right_foot.y;
    std::printf("step %zu (%s swings): left foot %+.4f m, right foot %+.4f m, capture y %+.4f\n",
                i + 1, calm.step_ends[i].swing == Foot::kLeft ? "left" : "right", left, right,
                tilted.step_ends[i].capture_y);
    if (i < first) {
      EXPECT_EQ(left, 0.0) << i;  // before the tilt: the same walk
      EXPECT_EQ(right, 0.0) << i;
    }
    if (i >= first && calm.step_ends[i].swing == Foot::kRight && right_shift == 0.0)
      right_shift = right;
    EXPECT_EQ(off.step_ends[i].right_foot.y, calm.step_ends[i].right_foot.y) << i;
    EXPECT_EQ(off.step_ends[i].left_foot.y, calm.step_ends[i].left_foot.y) << i;
  }
  // Measured: the first right step after the tilt lands 17.5 mm further right (the capture
  // point's deviation then, -19 mm, times step_gain_y 1).
  EXPECT_NEAR(right_shift, -0.0175, 0.001);
  EXPECT_GE(right_shift, -0.04 - 1e-9);  // walk.capture.max_step_y
}

TEST(WalkCaptureStep, InTheWalkEngineALateralTiltChangesTheStepTiming) {
  const std::vector<ParamWrite> timing{{"walk.capture.timing_gain", 10.0}};
  const EngineWalk calm = walk_engine(timing, 1e9, 0.0);
  const EngineWalk tilted = walk_engine(timing, 8.0, 0.05);
  const EngineWalk off = walk_engine({}, 8.0, 0.05);
  EXPECT_EQ(off.step_starts, walk_engine({}, 1e9, 0.0).step_starts);
  const std::size_t first = first_step_after(calm, 8.0);
  ASSERT_LT(first + 2, calm.step_starts.size());
  ASSERT_GT(first, 3u);
  for (std::size_t i = 0; i < first; ++i) EXPECT_EQ(tilted.step_starts[i], calm.step_starts[i]);
  std::printf("steps begin at ticks: calm");
  for (std::size_t i = first - 1; i < first + 3; ++i)
    std::printf(" %lld", static_cast<long long>(calm.step_starts[i]));
  std::printf(", tilted");
  for (std::size_t i = first - 1; i < first + 3; ++i)
    std::printf(" %lld", static_cast<long long>(tilted.step_starts[i]));
  std::printf("; phase rate %.3f..%.3f\n", tilted.min_phase_rate, tilted.max_phase_rate);
  // The step in flight at the tilt swings the left foot, away from where the capture point
  // goes: it lands later (measured 14 ticks); the next one, the right foot's, sooner (71 ticks
  // instead of 85); the calm walk keeps the clock's 85.
  ASSERT_EQ(calm.step_ends[first - 1].swing, Foot::kLeft);
  const auto duration = [](const EngineWalk& w, std::size_t i) {
    return w.step_starts[i + 1] - w.step_starts[i];
  };
  EXPECT_GE(tilted.step_starts[first] - calm.step_starts[first], 5);
  EXPECT_EQ(duration(calm, first), 85);
  EXPECT_LE(duration(tilted, first), 80);
  EXPECT_GE(duration(tilted, first), 85 / 1.3);  // walk.capture.max_timing 0.3
  EXPECT_GT(duration(tilted, first + 1), 85);    // the left foot's again: later
  EXPECT_GT(tilted.max_phase_rate, 1.05);
  EXPECT_LT(tilted.min_phase_rate, 0.95);
  EXPECT_GE(tilted.min_phase_rate, 0.7 - 1e-9);
  EXPECT_LE(tilted.max_phase_rate, 1.3 + 1e-9);
  EXPECT_EQ(calm.max_phase_rate, 1.0);  // no deviation, no change
  EXPECT_EQ(calm.min_phase_rate, 1.0);
}

TEST(WalkCaptureStep, UpdateAllocatesNothing) {
  Rig rig;
  rig.set("walk.capture.step_gain_y", 1.0);
  test::start_counting_allocations();
  rig.stand(0.5);
  rig.walk(2.0, 0.05, 0.02);
  (void)rig.capture.step_offset_y();
  EXPECT_EQ(test::stop_counting_allocations(), 0U);
}

}  // namespace
}  // namespace stride::fw::walk
