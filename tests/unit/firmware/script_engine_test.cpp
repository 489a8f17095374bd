// ScriptEngine: frame deadlines in ticks, moving speeds from the time left, gain and torque
// mapping, the duration modifier, untouched servos and determinism.
#include <cmath>

#include <gtest/gtest.h>

#include "stride/firmware/script/script_engine.hpp"
#include "stride/firmware/stand_pose.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw {
namespace {

constexpr std::int64_t kPeriodNs = 10'000'000;  // 100 Hz
const ServoTable& servos() {
  return ServoTable::defaults();
}
std::size_t idx(const char* name) {
  return *servos().index_of(name);
}

// Frame 1 (100 ms): r_knee -> 1.0 (gain 20, torque 50); frame 2 (50 ms): r_knee -> 0.4 (gain 100),
// l_knee -> 0.8 (gain 30). l_knee is only in frame 2.
Script two_frame_script() {
  Script s;
  s.name = "probe";
  s.frames.push_back({100, {{idx("r_knee"), 1.0, 20, 50}}, {}, {}});
  s.frames.push_back({50, {{idx("r_knee"), 0.4, 100, 100}, {idx("l_knee"), 0.8, 30, 100}}, {}, {}});
  return s;
}

struct Fixture {
  ParameterStore params;
  ScriptEngine engine{kPeriodNs, params};
  hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();
  hal::CommandFrame out{};

  explicit Fixture(Script script = two_frame_script()) {
    const Status status = engine.add_script(std::move(script));
    if (!status) ADD_FAILURE() << status.message();
    EXPECT_TRUE(engine.select(engine.find("probe")));
  }
  void step(hal::Tick tick) { engine.step(sensors, tick, out); }
};

TEST(ScriptEngine, DeadlinesAreCumulativeFrameDurationsInTicks) {
  Fixture f;
  f.engine.start(f.sensors, f.out, 5);
  EXPECT_EQ(f.engine.deadline(0), 15);  // 5 + 100 ms / 10 ms
  EXPECT_EQ(f.engine.deadline(1), 20);  // 5 + 150 ms / 10 ms
  EXPECT_EQ(f.engine.end_tick(), 20);
  EXPECT_FALSE(f.engine.done());
}

TEST(ScriptEngine, SpeedIsDeltaOverTimeLeftFixedWhenTheTargetBecomesFront) {
  Fixture f;
  f.sensors.servos[idx("r_knee")].position_rad = 0.0;
  f.sensors.servos[idx("l_knee")].position_rad = 0.2;
  f.engine.start(f.sensors, f.out, 5);
  f.step(5);
  const auto& rk = f.out.servos[idx("r_knee")];
  EXPECT_DOUBLE_EQ(rk.position_rad, 1.0);
  EXPECT_NEAR(rk.moving_speed_rad_s, 1.0 / 0.1, 1e-12);  // |1 - 0| / (10 ticks * 10 ms)
  EXPECT_DOUBLE_EQ(rk.p_gain, 51);                       // round(2.54 * 20)
  EXPECT_DOUBLE_EQ(rk.i_gain, 0);
  EXPECT_DOUBLE_EQ(rk.d_gain, 0);
  EXPECT_DOUBLE_EQ(rk.torque_limit, 0.5);
  EXPECT_TRUE(rk.torque_enable);
  // l_knee's front target is frame 2's: |0.8 - 0.2| over the 15 ticks to its deadline.
  const auto& lk = f.out.servos[idx("l_knee")];
  EXPECT_DOUBLE_EQ(lk.position_rad, 0.8);
  EXPECT_NEAR(lk.moving_speed_rad_s, 0.6 / 0.15, 1e-12);
  EXPECT_DOUBLE_EQ(lk.p_gain, 76);  // round(2.54 * 30)

  // Mid-frame the speed stays what it was set to (the servo was told once), whatever the
  // present position.
  f.sensors.servos[idx("r_knee")].position_rad = 0.7;
  f.step(14);
  EXPECT_NEAR(f.out.servos[idx("r_knee")].moving_speed_rad_s, 10.0, 1e-12);
  EXPECT_FALSE(f.engine.done());

  // At the frame-1 deadline (tick 15) frame 2 becomes front: |0.4 - 0.7| over 5 ticks.
  f.sensors.servos[idx("r_knee")].position_rad = 0.7;
  f.step(15);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_knee")].position_rad, 0.4);
  EXPECT_NEAR(f.out.servos[idx("r_knee")].moving_speed_rad_s, 0.3 / 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_knee")].p_gain, 254);  // g = 100 caps at 254
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_knee")].torque_limit, 1.0);
  EXPECT_FALSE(f.engine.done());

  // After the last deadline: hold the last target at full speed (0), done.
  f.step(20);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_knee")].position_rad, 0.4);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_knee")].moving_speed_rad_s, 0.0);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("l_knee")].moving_speed_rad_s, 0.0);
  EXPECT_TRUE(f.engine.done());
}

TEST(ScriptEngine, LateStartOfAFrameUsesTheTimeActuallyLeft) {
  // The loop skipped ticks 5..11: the first step at tick 12 has 3 ticks left to deadline 15.
  Fixture f;
  f.sensors.servos[idx("r_knee")].position_rad = 0.4;
  f.engine.start(f.sensors, f.out, 5);
  f.step(12);
  EXPECT_NEAR(f.out.servos[idx("r_knee")].moving_speed_rad_s, 0.6 / 0.03, 1e-9);
  // A step that lands after frame 1's deadline goes straight to frame 2.
  Fixture g;
  g.engine.start(g.sensors, g.out, 5);
  g.step(17);
  EXPECT_DOUBLE_EQ(g.out.servos[idx("r_knee")].position_rad, 0.4);
  EXPECT_NEAR(g.out.servos[idx("r_knee")].moving_speed_rad_s, 0.4 / 0.03, 1e-9);
}

TEST(ScriptEngine, ZeroDeltaGetsTheSmallestNonZeroSpeed) {
  Fixture f;
  f.sensors.servos[idx("r_knee")].position_rad = 1.0;
  f.engine.start(f.sensors, f.out, 0);
  f.step(0);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_knee")].moving_speed_rad_s, ScriptEngine::kMinMovingSpeed);
  EXPECT_NEAR(ScriptEngine::kMinMovingSpeed, 0.01199, 1e-5);
}

TEST(ScriptEngine, ServoThatDidNotAnswerStartsFromTheLastCommand) {
  Fixture f;
  f.sensors.servos[idx("r_knee")].position_rad = 0.0;
  f.sensors.servos[idx("r_knee")].health = hal::DeviceHealth::kTimeout;
  f.out.servos[idx("r_knee")].position_rad = 0.5;
  f.engine.start(f.sensors, f.out, 0);
  f.step(0);
  EXPECT_NEAR(f.out.servos[idx("r_knee")].moving_speed_rad_s, 0.5 / 0.1, 1e-12);
}

TEST(ScriptEngine, TorqueZeroSwitchesTheServoOff) {
  Script s;
  s.name = "probe";
  s.frames.push_back({30, {{idx("r_elbow"), -1.0, 0, 0}}, {}, {}});
  Fixture f(std::move(s));
  f.out.servos[idx("r_elbow")].torque_enable = true;
  f.engine.start(f.sensors, f.out, 0);
  f.step(0);
  EXPECT_FALSE(f.out.servos[idx("r_elbow")].torque_enable);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_elbow")].torque_limit, 0.0);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_elbow")].p_gain, 0.0);
}

TEST(ScriptEngine, ServosNotInTheScriptAreLeftUntouched) {
  Fixture f;
  hal::ServoCommand head{};
  head.position_rad = 0.25;
  head.moving_speed_rad_s = 1.5;
  head.p_gain = 12;
  head.torque_enable = true;
  f.out.servos[idx("head_yaw")] = head;
  f.engine.start(f.sensors, f.out, 0);
  for (hal::Tick t = 0; t < 20; ++t) f.step(t);
  const auto& after = f.out.servos[idx("head_yaw")];
  EXPECT_DOUBLE_EQ(after.position_rad, 0.25);
  EXPECT_DOUBLE_EQ(after.moving_speed_rad_s, 1.5);
  EXPECT_DOUBLE_EQ(after.p_gain, 12);
  EXPECT_TRUE(after.torque_enable);
}

TEST(ScriptEngine, DurationModifierScalesEveryDeadline) {
  Fixture f;
  ASSERT_TRUE(f.params.stage("script.duration_modifier", 2.0));
  ASSERT_TRUE(f.params.apply_staged());
  f.engine.start(f.sensors, f.out, 5);
  EXPECT_EQ(f.engine.deadline(0), 25);
  EXPECT_EQ(f.engine.deadline(1), 35);
  f.sensors.servos[idx("r_knee")].position_rad = 0.0;
  f.step(5);
  EXPECT_NEAR(f.out.servos[idx("r_knee")].moving_speed_rad_s, 1.0 / 0.2, 1e-12);
  // Out-of-range modifiers are refused by the store.
  EXPECT_FALSE(f.params.stage("script.duration_modifier", 0.0));
}

TEST(ScriptEngine, EachFrameDurationIsAParameterReadAtStart) {
  Fixture f;
  EXPECT_EQ(f.params.value(*f.params.find("script.probe.frame2.duration_ms")), 50.0);
  ASSERT_TRUE(f.params.stage("script.probe.frame1.duration_ms", 40.0));
  ASSERT_TRUE(f.params.apply_staged());
  f.engine.start(f.sensors, f.out, 5);
  EXPECT_EQ(f.engine.deadline(0), 9);   // 5 + 40 ms / 10 ms
  EXPECT_EQ(f.engine.deadline(1), 14);  // 5 + 90 ms / 10 ms
  // Outside 1..60000 ms the store refuses it and nothing changes.
  EXPECT_FALSE(f.params.stage("script.probe.frame1.duration_ms", 0.0));
  EXPECT_FALSE(f.params.stage("script.probe.frame1.duration_ms", 60001.0));
  EXPECT_EQ(f.params.value(*f.params.find("script.probe.frame1.duration_ms")), 40.0);
}

TEST(ScriptEngine, EveryFrameGetsAtLeastOneTick) {
  Script s;
  s.name = "probe";
  s.frames.push_back({3, {{idx("r_knee"), 0.5, 20, 100}}, {}, {}});
  s.frames.push_back({3, {{idx("r_knee"), 0.6, 20, 100}}, {}, {}});
  s.frames.push_back({3, {{idx("r_knee"), 0.7, 20, 100}}, {}, {}});
  Fixture f(std::move(s));
  f.engine.start(f.sensors, f.out, 0);
  EXPECT_EQ(f.engine.deadline(0), 1);
  EXPECT_EQ(f.engine.deadline(1), 2);
  EXPECT_EQ(f.engine.deadline(2), 3);
  f.step(0);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_knee")].position_rad, 0.5);
  f.step(1);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_knee")].position_rad, 0.6);
  f.step(2);
  EXPECT_DOUBLE_EQ(f.out.servos[idx("r_knee")].position_rad, 0.7);
}

TEST(ScriptEngine, SelectFindAndNothingSelected) {
  ParameterStore params;
  ScriptEngine engine(kPeriodNs, params);
  EXPECT_EQ(engine.find("probe"), -1);
  EXPECT_FALSE(engine.select(0));
  hal::CommandFrame out{};
  out.servos[0].position_rad = 0.3;
  engine.start(hal::ScriptedRobot::standing_frame(), out, 0);
  engine.step(hal::ScriptedRobot::standing_frame(), 0, out);
  EXPECT_TRUE(engine.done());
  EXPECT_DOUBLE_EQ(out.servos[0].position_rad, 0.3);
  ASSERT_TRUE(engine.add_script(two_frame_script()));
  EXPECT_EQ(engine.find("probe"), 0);
  EXPECT_FALSE(engine.select(1));
  EXPECT_FALSE(engine.select(-1));
  EXPECT_TRUE(engine.select(0));
}

TEST(ScriptEngine, AddScriptIsAllOrNothing) {
  ParameterStore params;
  ScriptEngine engine(kPeriodNs, params);
  ASSERT_TRUE(engine.add_script(two_frame_script()));
  const auto size = params.size();
  const Status dup = engine.add_script(two_frame_script());
  ASSERT_FALSE(dup);
  EXPECT_NE(dup.message().find("probe"), std::string::npos);
  EXPECT_EQ(params.size(), size);
  EXPECT_EQ(engine.script_count(), 1u);
  EXPECT_THROW(ScriptEngine(0, params), std::invalid_argument);
}

TEST(ScriptEngine, StockKickTimingAt100Hz) {
  ParameterStore params;
  ScriptEngine engine(kPeriodNs, params);
  const Status status = engine.load_folder(default_script_folder());
  ASSERT_TRUE(status) << status.message();
  ASSERT_TRUE(engine.select(engine.find("kick_right")));
  hal::CommandFrame out{};
  const hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();
  engine.start(sensors, out, 100);
  const hal::Tick expected[] = {200, 260, 290, 310, 360, 410};
  for (std::size_t f = 0; f < 6; ++f) EXPECT_EQ(engine.deadline(f), expected[f]) << f;
  hal::Tick ticks = 0;
  for (hal::Tick t = 100; !engine.done(); ++t, ++ticks) engine.step(sensors, t, out);
  EXPECT_EQ(ticks, 311);  // ticks 100..410
}

TEST(ScriptEngine, SameInputsSameCommands) {
  auto run = [] {
    Fixture f;
    hal::SensorFrame sensors = f.sensors;
    f.engine.start(sensors, f.out, 3);
    std::vector<double> trace;
    for (hal::Tick t = 3; t < 30; ++t) {
      sensors.servos[idx("r_knee")].position_rad = 0.01 * static_cast<double>(t);
      f.engine.step(sensors, t, f.out);
      for (const auto& c : f.out.servos) {
        trace.push_back(c.position_rad);
        trace.push_back(c.moving_speed_rad_s);
      }
    }
    return trace;
  };
  EXPECT_EQ(run(), run());
}

TEST(ScriptGainMapping, MatchesTheIgusRegisterConversion) {
  EXPECT_DOUBLE_EQ(gain_to_p_register(0), 0);
  EXPECT_DOUBLE_EQ(gain_to_p_register(20), 51);
  EXPECT_DOUBLE_EQ(gain_to_p_register(30), 76);
  EXPECT_DOUBLE_EQ(gain_to_p_register(99.9), 254);
  EXPECT_DOUBLE_EQ(gain_to_p_register(100), 254);
  EXPECT_DOUBLE_EQ(torque_limit_from_percent(100), 1.0);
  EXPECT_DOUBLE_EQ(torque_limit_from_percent(25), 0.25);
}

}  // namespace
}  // namespace stride::fw
