// SafetyLayer: joint limits, NaN guard, torque limits, error torque-off and fall detection.
#include "stride/firmware/safety_layer.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "firmware_fixture.hpp"

namespace stride::fw {
namespace {

class SafetyLayerTest : public ::testing::Test {
 protected:
  ParameterStore params;
  const ServoTable& table = ServoTable::defaults();
  AttitudeEstimator attitude{params, 0.01};
  SafetyLayer safety{params, table};
  hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();

  /// One tick of fall detection as the controller runs it: the attitude estimate first.
  void observe(const hal::SensorFrame& frame) {
    attitude.update(frame.cm730);
    safety.observe(frame, attitude);
  }

  hal::CommandFrame valid_commands() {
    hal::CommandFrame c;
    for (auto& s : c.servos) {
      s.torque_enable = true;
      s.position_rad = 0.0;
    }
    return c;
  }
};

TEST_F(SafetyLayerTest, ClampsToJointLimitsAndCounts) {
  auto c = valid_commands();
  const std::size_t knee = *table.index_of("r_knee");
  c.servos[knee].position_rad = 5.0;
  c.servos[0].position_rad = -7.0;
  safety.apply(sensors, c);
  EXPECT_DOUBLE_EQ(c.servos[knee].position_rad, table[knee].max_rad);
  EXPECT_DOUBLE_EQ(c.servos[0].position_rad, table[0].min_rad);
  EXPECT_EQ(safety.report().limit_clamps[knee], 1u);
  EXPECT_EQ(safety.report().limit_clamps[1], 0u);
}

TEST_F(SafetyLayerTest, NanTargetHoldsLastSafeValue) {
  auto c = valid_commands();
  c.servos[7].position_rad = 0.3;
  safety.apply(sensors, c);
  c.servos[7].position_rad = std::nan("");
  c.servos[7].moving_speed_rad_s = INFINITY;
  c.servos[7].p_gain = std::nan("");
  safety.apply(sensors, c);
  EXPECT_DOUBLE_EQ(c.servos[7].position_rad, 0.3);
  EXPECT_DOUBLE_EQ(c.servos[7].moving_speed_rad_s, 0.0);
  EXPECT_DOUBLE_EQ(c.servos[7].p_gain, 0.0);
  EXPECT_EQ(safety.report().nan_targets[7], 1u);
}

TEST_F(SafetyLayerTest, NanOnFirstTickFallsBackToMeasuredPosition) {
  auto c = valid_commands();
  sensors.servos[2].position_rad = -0.2;
  c.servos[2].position_rad = std::nan("");
  safety.apply(sensors, c);
  EXPECT_DOUBLE_EQ(c.servos[2].position_rad, -0.2);
}

TEST_F(SafetyLayerTest, TorqueLimitAndGainFollowParameters) {
  ASSERT_TRUE(params.set_now({{"safety.max_torque_limit", 0.5}, {"safety.max_p_gain", 100}}));
  auto c = valid_commands();
  c.servos[3].torque_limit = 0.9;
  c.servos[3].p_gain = 200;
  safety.apply(sensors, c);
  EXPECT_DOUBLE_EQ(c.servos[3].torque_limit, 0.5);
  EXPECT_DOUBLE_EQ(c.servos[3].p_gain, 100);
  EXPECT_GE(safety.report().torque_clamps, 1u);
}

TEST_F(SafetyLayerTest, PersistentErrorFlagsSwitchTheServoOffUntilReset) {
  ASSERT_TRUE(params.set_now({{"safety.error_ticks", 3}}));
  sensors.servos[12].error_flags = hal::error_bits::kOverheating;
  for (int i = 0; i < 2; ++i) {
    auto c = valid_commands();
    safety.apply(sensors, c);
    EXPECT_TRUE(c.servos[12].torque_enable) << "tick " << i;
  }
  auto c = valid_commands();
  safety.apply(sensors, c);
  EXPECT_FALSE(c.servos[12].torque_enable);
  EXPECT_TRUE(safety.report().torque_off_latched[12]);
  sensors.servos[12].error_flags = 0;  // the flag clears, the latch stays
  c = valid_commands();
  safety.apply(sensors, c);
  EXPECT_FALSE(c.servos[12].torque_enable);
  safety.reset_latches();
  c = valid_commands();
  safety.apply(sensors, c);
  EXPECT_TRUE(c.servos[12].torque_enable);
}

TEST_F(SafetyLayerTest, AngleLimitErrorsDoNotSwitchOffByDefault) {
  ASSERT_TRUE(params.set_now({{"safety.error_ticks", 1}}));
  sensors.servos[5].error_flags = hal::error_bits::kAngleLimit;
  auto c = valid_commands();
  safety.apply(sensors, c);
  safety.apply(sensors, c);
  EXPECT_TRUE(c.servos[5].torque_enable);
}

TEST_F(SafetyLayerTest, DetectsFallAfterPersistentTiltAndRecovers) {
  const auto upright = test::tilted_frame(0.05);
  const auto lying = test::tilted_frame(1.5);
  for (int i = 0; i < 20; ++i) observe(upright);
  EXPECT_FALSE(safety.fallen());
  observe(lying);
  EXPECT_FALSE(safety.fallen()) << "a single tilted sample is not a fall";
  for (int i = 0; i < 40; ++i) observe(lying);
  EXPECT_TRUE(safety.fallen());
  EXPECT_EQ(safety.report().falls, 1u);
  for (int i = 0; i < 40; ++i) observe(upright);
  EXPECT_FALSE(safety.fallen());
}

TEST_F(SafetyLayerTest, IgnoresMissingImuReadings) {
  hal::SensorFrame zero = sensors;
  zero.cm730.accel_mps2 = {0.0, 0.0, 0.0};
  for (int i = 0; i < 50; ++i) observe(zero);
  EXPECT_FALSE(safety.fallen());
  zero.cm730.accel_mps2 = {NAN, 0.0, 9.8};
  for (int i = 0; i < 50; ++i) observe(zero);
  EXPECT_FALSE(safety.fallen());
}

}  // namespace
}  // namespace stride::fw
