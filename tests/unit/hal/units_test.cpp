// Register <-> SI conversions checked against igus.md section 6 (and 1.5 for positions).
#include <gtest/gtest.h>

#include <cmath>

#include "stride/hal/dynamixel/units.hpp"

namespace stride::hal::dxl {
namespace {

using namespace units;

TEST(Units, PositionUsesDirectionOffsetAnd4096Ticks) {
  const ServoCalibration plain{1, 0.0, ServoModelId::kMx106};
  EXPECT_EQ(position_to_ticks(0.0, plain), 2048);
  EXPECT_EQ(position_to_ticks(kPi / 2, plain), 3072);  // a quarter turn is 1024 ticks
  EXPECT_EQ(position_to_ticks(-kPi / 2, plain), 1024);
  // r_shoulder_pitch: direction -1, offset -pi/4. The Stand pose's 0.3927 rad (URDF) is
  // ticks = -(0.3927 + 0.785398) * 4096 / (2 pi) + 2048 = 1280.
  const ServoCalibration shoulder{-1, -0.785398, ServoModelId::kMx64};
  EXPECT_EQ(position_to_ticks(0.3927, shoulder), 1280);
  EXPECT_EQ(position_to_ticks(-0.785398, shoulder), 2048);
  // Round trip within half a tick for angles around the offset.
  for (double a = -3.0; a <= 3.0; a += 0.01) {
    const ServoCalibration knee{-1, kPi / 8, ServoModelId::kMx106};
    const double back = ticks_to_position(position_to_ticks(a, knee), knee);
    double diff = std::remainder(back - a, 2 * kPi);
    EXPECT_LE(std::abs(diff), kRadPerTick / 2 + 1e-12) << a;
  }
  // Angles wrap: a + 2 pi gives the same ticks.
  EXPECT_EQ(position_to_ticks(3.0, shoulder), position_to_ticks(3.0 - 2 * kPi, shoulder));
  EXPECT_EQ(position_to_ticks(NAN, plain), 2048);
}

TEST(Units, MovingSpeed) {
  // 1023 units = 116.62 rpm (0.114 rpm per unit).
  EXPECT_NEAR(moving_speed_from_register(1023) * 60 / (2 * kPi), 116.622, 1e-3);
  EXPECT_EQ(moving_speed_to_register(0.0), 0);  // 0 = full speed
  EXPECT_EQ(moving_speed_to_register(-1.0), 0);
  EXPECT_EQ(moving_speed_to_register(1e-6), 1);  // never rounds a real limit to "no limit"
  EXPECT_EQ(moving_speed_to_register(100.0), 1023);
  EXPECT_EQ(moving_speed_to_register(1.0), 84);  // 1 rad/s / 0.011938 = 83.77
}

TEST(Units, PresentSpeedAndLoadCarryDirectionInBit10) {
  const ServoCalibration plus{1, 0.0, ServoModelId::kMx106};
  const ServoCalibration minus{-1, 0.0, ServoModelId::kMx106};
  EXPECT_NEAR(present_speed_from_register(100, plus), 100 * kSpeedUnitRadS, 1e-12);
  EXPECT_NEAR(present_speed_from_register(1024 + 100, plus), -100 * kSpeedUnitRadS, 1e-12);
  EXPECT_NEAR(present_speed_from_register(100, minus), -100 * kSpeedUnitRadS, 1e-12);
  EXPECT_NEAR(load_from_register(1023, plus), 1.0, 1e-12);
  EXPECT_NEAR(load_from_register(1024 + 512, plus), -512.0 / 1023, 1e-12);
  EXPECT_EQ(load_to_register(-512.0 / 1023, plus), 1024 + 512);
  EXPECT_EQ(present_speed_to_register(-100 * kSpeedUnitRadS, plus), 1024 + 100);
}

TEST(Units, GainsTorqueVoltageTemperature) {
  EXPECT_EQ(script_gain_to_register(100), 254);  // P = round(2.54 g)
  EXPECT_EQ(script_gain_to_register(50), 127);
  EXPECT_EQ(gain_to_register(300), 254);
  EXPECT_DOUBLE_EQ(kp_from_p_register(32), 4.0);       // Kp = P/8
  EXPECT_DOUBLE_EQ(ki_from_i_register(2048), 1000.0);  // Ki = I*1000/2048
  EXPECT_DOUBLE_EQ(kd_from_d_register(250), 1.0);      // Kd = D*4/1000
  EXPECT_DOUBLE_EQ(v2_kpp_from_register(850), 850.0 / 128);
  EXPECT_DOUBLE_EQ(v2_kpi_from_register(65536), 1.0);
  EXPECT_DOUBLE_EQ(v2_kpd_from_register(16), 1.0);
  EXPECT_NEAR(v2_velocity_from_register(100) * 60 / (2 * kPi), 22.9, 1e-9);
  EXPECT_EQ(torque_limit_to_register(1.0), 1023);
  EXPECT_EQ(torque_limit_to_register(0.5), 512);
  EXPECT_EQ(torque_limit_to_register(2.0), 1023);
  EXPECT_NEAR(torque_limit_from_register(1023), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(voltage_from_register(148), 14.8);
  EXPECT_EQ(voltage_to_register(16.8), 168);
  EXPECT_DOUBLE_EQ(temperature_from_register(80), 80.0);
}

TEST(Units, Cm730Imu) {
  // accel = (raw - 512) * 4 g / 512: raw 640 is +1 g; gyro = (raw - 512) * 1800 deg/s / 512.
  EXPECT_NEAR(accel_from_raw(640), kStandardGravity, 1e-12);
  EXPECT_NEAR(accel_from_raw(512), 0.0, 1e-12);
  EXPECT_EQ(accel_to_raw(kStandardGravity), 640);
  EXPECT_NEAR(gyro_from_raw(512 + 256), 900.0 * kPi / 180.0, 1e-12);
  EXPECT_EQ(gyro_to_raw(-900.0 * kPi / 180.0), 256);
  EXPECT_EQ(gyro_to_raw(1e9), 1023);
}

}  // namespace
}  // namespace stride::hal::dxl
