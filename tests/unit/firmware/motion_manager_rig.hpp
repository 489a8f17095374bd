// The MotionManager test rig: the real ScriptEngine with the stock scripts (played as timed: no
// attitude estimate) and a small walk stand-in that takes a few ticks to finish its step after
// request_stop(), as a walk does; the sensors are set by hand (lying, upright).
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "stride/firmware/motion_manager.hpp"
#include "stride/firmware/script/script_engine.hpp"
#include "stride/firmware/stand_pose.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw::test {

constexpr std::int64_t kPeriodNs = 10'000'000;
constexpr double kPeriodS = 0.01;
constexpr hal::Tick kStandRampTicks = 150;  // stand.ramp_time 1.5 s default
inline std::size_t idx(const char* name) {
  return *ServoTable::defaults().index_of(name);
}

// Walk stand-in: marks the commands it writes (r_hip_yaw = kWalkMark) and finishes
// kStopTicks ticks after request_stop().
class StepWalk final : public WalkControl {
 public:
  static constexpr double kWalkMark = 0.123;
  static constexpr int kStopTicks = 20;
  std::string_view name() const noexcept override { return "walk"; }
  void start(const hal::SensorFrame&, const hal::CommandFrame&, hal::Tick) noexcept override {
    ++starts;
    stopping = false;
    stop_countdown = kStopTicks;
  }
  void step(const hal::SensorFrame&, hal::Tick, hal::CommandFrame& out) noexcept override {
    out.servos[idx("r_hip_yaw")].position_rad = kWalkMark;
    if (stopping && stop_countdown > 0) --stop_countdown;
  }
  bool done() const noexcept override { return stopping && stop_countdown == 0; }
  void set_velocity(double x, double y, double th) noexcept override {
    vx = x;
    vy = y;
    vth = th;
  }
  void request_stop() noexcept override {
    stopping = true;
    ++stop_requests;
  }
  int starts = 0, stop_requests = 0, stop_countdown = 0;
  bool stopping = false;
  double vx = 0, vy = 0, vth = 0;
};

struct Rig {
  ParameterStore params;
  ScriptEngine scripts{kPeriodNs, params};
  StepWalk walk;
  std::unique_ptr<MotionManager> manager;
  hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame(kStandPoseRad);
  hal::CommandFrame out{};
  hal::Tick tick = 0;
  bool fallen = false;

  explicit Rig(bool with_walk = true) {
    const Status s = scripts.load_folder(default_script_folder());
    if (!s) ADD_FAILURE() << s.message();
    manager =
        std::make_unique<MotionManager>(params, kPeriodS, with_walk ? &walk : nullptr, &scripts);
  }
  void run(hal::Tick ticks) {
    for (hal::Tick i = 0; i < ticks; ++i) manager->step(sensors, tick++, fallen, out);
  }
  // Runs until `state` or `limit` ticks; returns the ticks taken (limit + 1 if never).
  hal::Tick run_until(MotionState state, hal::Tick limit) {
    for (hal::Tick i = 0; i <= limit; ++i) {
      if (manager->state() == state) return i;
      manager->step(sensors, tick++, fallen, out);
    }
    return limit + 1;
  }
  void settle_stand() {
    run(kStandRampTicks + 2);
    ASSERT_EQ(manager->state(), MotionState::kStand);
    ASSERT_TRUE(manager->stand().done());
  }
  void lie(double ax, double ay, double az) {
    sensors.cm730.accel_mps2 = {ax, ay, az};
    fallen = true;
  }
  void get_up_upright() {
    sensors.cm730.accel_mps2 = {0.0, 0.0, 9.81};
    fallen = false;
  }
};

}  // namespace stride::fw::test
