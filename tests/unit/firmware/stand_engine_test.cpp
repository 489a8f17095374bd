// StandEngine: ramps from the measured pose to the stand pose over stand.ramp_time.
#include "stride/firmware/stand_engine.hpp"

#include <gtest/gtest.h>

#include "stride/firmware/stand_pose.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw {
namespace {

TEST(StandEngine, RampsFromMeasuredPoseToStandPoseAndSettles) {
  ParameterStore params;
  StandEngine stand(params, 0.01);
  ASSERT_TRUE(params.set_now({{"stand.ramp_time", 1.0}, {"stand.gain", 30}}));
  std::array<double, hal::kServoCount> start{};
  start[12] = 1.0;  // r_knee bent further than the stand pose
  const auto sensors = hal::ScriptedRobot::standing_frame(start);
  hal::CommandFrame out;  // torque off: start from the measured pose
  stand.start(sensors, out, 100);

  stand.step(sensors, 100, out);
  EXPECT_DOUBLE_EQ(out.servos[12].position_rad, 1.0);
  EXPECT_TRUE(out.servos[12].torque_enable);
  EXPECT_DOUBLE_EQ(out.servos[12].p_gain, 76.0);  // round(2.54 * 30)
  EXPECT_FALSE(stand.done());

  stand.step(sensors, 150, out);  // half way: smoothstep(0.5) = 0.5
  EXPECT_NEAR(out.servos[12].position_rad, 0.5 * (1.0 + kStandPoseRad[12]), 1e-12);
  EXPECT_FALSE(stand.done());

  stand.step(sensors, 200, out);
  EXPECT_DOUBLE_EQ(out.servos[12].position_rad, kStandPoseRad[12]);
  EXPECT_DOUBLE_EQ(out.servos[0].position_rad, kStandPoseRad[0]);
  EXPECT_TRUE(stand.done());
}

TEST(StandEngine, ContinuesFromTheLastHeldTarget) {
  ParameterStore params;
  StandEngine stand(params, 0.01);
  const auto sensors = hal::ScriptedRobot::standing_frame();
  hal::CommandFrame last;
  last.servos[3].position_rad = 0.7;
  last.servos[3].torque_enable = true;
  stand.start(sensors, last, 0);
  hal::CommandFrame out = last;
  stand.step(sensors, 0, out);
  EXPECT_DOUBLE_EQ(out.servos[3].position_rad, 0.7);
}

TEST(StandEngine, GainConversionMatchesNubots) {
  EXPECT_DOUBLE_EQ(gain_to_p_register(20), 51);
  EXPECT_DOUBLE_EQ(gain_to_p_register(30), 76);
  EXPECT_DOUBLE_EQ(gain_to_p_register(100), 254);
  EXPECT_DOUBLE_EQ(gain_to_p_register(150), 254);
  EXPECT_DOUBLE_EQ(gain_to_p_register(-5), 0);
}

}  // namespace
}  // namespace stride::fw
