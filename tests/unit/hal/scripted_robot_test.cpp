// ScriptedRobot: frames are fed in order, commands recorded, late wake-ups injected.
#include "stride/hal/scripted_robot.hpp"

#include <gtest/gtest.h>

namespace stride::hal {
namespace {

TEST(ScriptedRobot, FeedsFramesInOrderThenRepeatsTheLast) {
  SensorFrame a = ScriptedRobot::standing_frame();
  SensorFrame b = a;
  b.servos[0].position_rad = 0.5;
  ScriptedRobot robot({}, {a, b});
  SensorFrame out;
  robot.read(out);
  EXPECT_DOUBLE_EQ(out.servos[0].position_rad, 0.0);
  robot.read(out);
  EXPECT_DOUBLE_EQ(out.servos[0].position_rad, 0.5);
  robot.read(out);
  EXPECT_DOUBLE_EQ(out.servos[0].position_rad, 0.5);
  EXPECT_EQ(robot.reads(), 3u);
}

TEST(ScriptedRobot, RecordsCommandsUpToCapacity) {
  ScriptedRobot::Options options;
  options.record_capacity = 2;
  ScriptedRobot robot(options, {ScriptedRobot::standing_frame()});
  CommandFrame c;
  for (int i = 0; i < 3; ++i) {
    c.tick = i;
    robot.write(c);
  }
  ASSERT_EQ(robot.recorded().size(), 2u);
  EXPECT_EQ(robot.recorded()[1].tick, 1);
  EXPECT_EQ(robot.writes(), 3u);
}

TEST(ScriptedRobot, EchoMovesTowardsGoalAtMovingSpeed) {
  ScriptedRobot::Options options;
  options.echo_commands = true;
  options.period_ns = 10'000'000;
  ScriptedRobot robot(options, {ScriptedRobot::standing_frame()});
  CommandFrame c;
  c.servos[4].position_rad = 1.0;
  c.servos[4].moving_speed_rad_s = 10.0;  // 0.1 rad per 10 ms tick
  c.servos[4].torque_enable = true;
  robot.write(c);
  SensorFrame out;
  robot.read(out);
  EXPECT_NEAR(out.servos[4].position_rad, 0.1, 1e-12);
  robot.read(out);
  EXPECT_NEAR(out.servos[4].position_rad, 0.2, 1e-12);
}

TEST(ScriptedRobot, InjectedLateWakeupIsReported) {
  ScriptedRobot robot({}, {ScriptedRobot::standing_frame()});
  robot.inject_late_wakeup(5, 8);
  EXPECT_EQ(robot.sleep_until(4), 4);
  EXPECT_EQ(robot.sleep_until(5), 8);
}

TEST(ScriptedRobot, RejectsEmptyScript) {
  EXPECT_THROW(ScriptedRobot({}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace stride::hal
