// Control tables against igus.md 6.2-6.4.
#include <gtest/gtest.h>

#include "stride/hal/dynamixel/control_table.hpp"

namespace stride::hal::dxl {
namespace {

void expect_register(const ControlTable& t, const char* name, std::uint16_t address,
                     std::uint8_t size, std::uint32_t initial) {
  const Register* r = t.find(name);
  ASSERT_NE(r, nullptr) << t.model_name << " " << name;
  EXPECT_EQ(r->address, address) << name;
  EXPECT_EQ(r->size, size) << name;
  EXPECT_EQ(r->initial, initial) << name;
  EXPECT_EQ(t.at(address), r);
}

TEST(ControlTable, Mx1) {
  for (const ControlTable* t : {&mx64_v1_table(), &mx106_v1_table()}) {
    expect_register(*t, "return_delay_time", mx1::kReturnDelayTime, 1, 250);
    expect_register(*t, "status_return_level", 16, 1, 2);
    expect_register(*t, "temperature_limit", 11, 1, 80);
    expect_register(*t, "shutdown", 18, 1, 36);
    expect_register(*t, "d_gain", 26, 1, 0);
    expect_register(*t, "p_gain", 28, 1, 32);
    expect_register(*t, "goal_position", 30, 2, 2048);
    expect_register(*t, "moving_speed", 32, 2, 0);
    expect_register(*t, "torque_limit", 34, 2, 1023);
    expect_register(*t, "present_position", 36, 2, 2048);
    expect_register(*t, "present_temperature", 43, 1, 35);
    EXPECT_EQ(t->covering(29), nullptr);  // reserved between P gain and goal position
    EXPECT_EQ(t->covering(31)->name, "goal_position");
  }
  EXPECT_EQ(mx64_v1_table().model_number, 310);
  EXPECT_EQ(mx106_v1_table().model_number, 320);
  EXPECT_NE(mx106_v1_table().find("drive_mode"), nullptr);
  EXPECT_EQ(mx64_v1_table().find("drive_mode"), nullptr);
}

TEST(ControlTable, Mx2) {
  for (const ControlTable* t : {&mx64_v2_table(), &mx106_v2_table()}) {
    expect_register(*t, "id", 7, 1, 1);
    expect_register(*t, "return_delay_time", 9, 1, 250);
    expect_register(*t, "operating_mode", 11, 1, 3);
    expect_register(*t, "torque_enable", 64, 1, 0);
    expect_register(*t, "position_p_gain", 84, 2, 850);
    expect_register(*t, "profile_velocity", 112, 4, 0);
    expect_register(*t, "goal_position", 116, 4, 2048);
    expect_register(*t, "present_position", 132, 4, 2048);
    expect_register(*t, "present_temperature", 146, 1, 35);
  }
  EXPECT_EQ(mx64_v2_table().model_number, 311);
  EXPECT_EQ(mx106_v2_table().model_number, 321);
  EXPECT_EQ(mx64_v2_table().find("current_limit")->initial, 1941U);
  EXPECT_EQ(mx106_v2_table().find("current_limit")->initial, 2047U);
}

TEST(ControlTable, Cm730) {
  const ControlTable& t = cm730_table();
  expect_register(t, "dynamixel_power", 24, 1, 0);
  expect_register(t, "button", 30, 1, 0);
  expect_register(t, "gyro_z", 38, 2, 512);
  expect_register(t, "gyro_y", 40, 2, 512);
  expect_register(t, "gyro_x", 42, 2, 512);
  expect_register(t, "accel_x", 44, 2, 512);
  expect_register(t, "accel_y", 46, 2, 512);
  expect_register(t, "accel_z", 48, 2, 640);
  expect_register(t, "present_voltage", 50, 1, 150);
  EXPECT_EQ(t.find("id")->initial, 200U);
  EXPECT_EQ(table_for_model(cm730::kModel, Protocol::kV1), &t);
  EXPECT_EQ(table_for_model(320, Protocol::kV2), nullptr);
}

TEST(ControlTable, RegistersDoNotOverlap) {
  for (const ControlTable* t :
       {&mx64_v1_table(), &mx106_v1_table(), &mx64_v2_table(), &mx106_v2_table(), &cm730_table()}) {
    for (std::uint16_t a = 0; a < t->size; ++a) {
      int covering = 0;
      for (const Register& r : t->registers) covering += (a >= r.address && a < r.address + r.size);
      EXPECT_LE(covering, 1) << t->model_name << " address " << a;
    }
    for (const Register& r : t->registers) {
      EXPECT_LE(r.address + r.size, t->size) << t->model_name << " " << r.name;
      EXPECT_LE(r.min, r.max) << r.name;
    }
  }
}

}  // namespace
}  // namespace stride::hal::dxl
