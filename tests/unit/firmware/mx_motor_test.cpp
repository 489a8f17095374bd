// The MX motor table against the figures of ../shared/robot/servos.md (rounded there).
#include "stride/firmware/mx_motor.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace stride::fw {
namespace {

TEST(MxMotor, HoldsTheIdentifiedFiguresOfServosMd) {
  // servos.md's M6 and M1 table (4 or 5 significant figures).
  EXPECT_NEAR(kMx106.m6.torque_constant, 2.2098, 5e-5);
  EXPECT_NEAR(kMx106.m6.resistance_ohm, 2.0337, 5e-5);
  EXPECT_NEAR(kMx106.m6.armature_kg_m2, 0.026016, 5e-7);
  EXPECT_NEAR(kMx64.m6.torque_constant, 1.6017, 5e-5);
  EXPECT_NEAR(kMx64.m6.resistance_ohm, 2.3164, 5e-5);
  EXPECT_NEAR(kMx64.m6.armature_kg_m2, 0.012266, 5e-7);
  EXPECT_NEAR(kMx106.m1.torque_constant, 2.1914, 5e-5);
  EXPECT_NEAR(kMx106.m1.resistance_ohm, 2.9650, 5e-5);
  EXPECT_NEAR(kMx106.m1.armature_kg_m2, 0.026609, 5e-7);
}

TEST(MxMotor, HoldsTheDatasheetFigures) {
  EXPECT_EQ(kMx64.gear_ratio, 200.0);
  EXPECT_EQ(kMx106.gear_ratio, 225.0);
  EXPECT_EQ(kMxDatasheetVolts[2], 14.8);
  EXPECT_EQ(kMx64.stall_torque_nm[2], 7.3);
  EXPECT_EQ(kMx106.stall_torque_nm[2], 10.0);
  EXPECT_EQ(kMx64.no_load_speed_rpm[0], 58.0);
  EXPECT_EQ(kMx106.no_load_speed_rpm[1], 45.0);
  EXPECT_NEAR(kMxBacklashRad * 180.0 / 3.14159265358979323846 * 60.0, 19.8, 1e-9);  // 20 arcmin
  EXPECT_EQ(&mx_motor(ServoModel::kMx64), &kMx64);
  EXPECT_EQ(&mx_motor(ServoModel::kMx106), &kMx106);
}

}  // namespace
}  // namespace stride::fw
