// Control table data of the MX-64/MX-106 (1.0 and 2.0 firmware), the stock CM730 and the CM730
// with NimbRo's firmware. Figures: igus.md 6.2 (MX 1.0), 6.3 (MX 2.0), 6.4 (CM730 as NUbots
// uses it), 6.5 (NimbRo's CM730), and the ROBOTIS e-manual MX pages for initial values and
// ranges not listed there.
#include "stride/hal/dynamixel/control_table.hpp"

#include <array>

namespace stride::hal::dxl {

namespace {

constexpr Access R = Access::kRead;
constexpr Access RW = Access::kReadWrite;
constexpr Memory E = Memory::kEeprom;
constexpr Memory M = Memory::kRam;

// Registers common to MX-64 and MX-106 on the 1.0 firmware; the model-specific rows differ.
#define STRIDE_MX1_COMMON(model, max_voltage)                                                   \
  Register{"model_number", 0, 2, R, E, model, model, model},                                    \
      Register{"firmware_version", 2, 1, R, E, 41, 0, 255},                                     \
      Register{"id", 3, 1, RW, E, 1, 0, 252}, Register{"baud_rate", 4, 1, RW, E, 34, 0, 254},   \
      Register{"return_delay_time", 5, 1, RW, E, 250, 0, 254},                                  \
      Register{"cw_angle_limit", 6, 2, RW, E, 0, 0, 4095},                                      \
      Register{"ccw_angle_limit", 8, 2, RW, E, 4095, 0, 4095},                                  \
      Register{"temperature_limit", 11, 1, RW, E, 80, 0, 100},                                  \
      Register{"min_voltage_limit", 12, 1, RW, E, 60, 50, 160},                                 \
      Register{"max_voltage_limit", 13, 1, RW, E, max_voltage, 50, 160},                        \
      Register{"max_torque", 14, 2, RW, E, 1023, 0, 1023},                                      \
      Register{"status_return_level", 16, 1, RW, E, 2, 0, 2},                                   \
      Register{"alarm_led", 17, 1, RW, E, 36, 0, 127},                                          \
      Register{"shutdown", 18, 1, RW, E, 36, 0, 127},                                           \
      Register{"multi_turn_offset", 20, 2, RW, E, 0, 0, 65535},                                 \
      Register{"resolution_divider", 22, 1, RW, E, 1, 1, 4},                                    \
      Register{"torque_enable", 24, 1, RW, M, 0, 0, 1}, Register{"led", 25, 1, RW, M, 0, 0, 1}, \
      Register{"d_gain", 26, 1, RW, M, 0, 0, 254}, Register{"i_gain", 27, 1, RW, M, 0, 0, 254}, \
      Register{"p_gain", 28, 1, RW, M, 32, 0, 254},                                             \
      Register{"goal_position", 30, 2, RW, M, 2048, 0, 4095},                                   \
      Register{"moving_speed", 32, 2, RW, M, 0, 0, 1023},                                       \
      Register{"torque_limit", 34, 2, RW, M, 1023, 0, 1023},                                    \
      Register{"present_position", 36, 2, R, M, 2048, 0, 4095},                                 \
      Register{"present_speed", 38, 2, R, M, 0, 0, 2047},                                       \
      Register{"present_load", 40, 2, R, M, 0, 0, 2047},                                        \
      Register{"present_voltage", 42, 1, R, M, 150, 0, 255},                                    \
      Register{"present_temperature", 43, 1, R, M, 35, 0, 255},                                 \
      Register{"registered", 44, 1, R, M, 0, 0, 1}, Register{"moving", 46, 1, R, M, 0, 0, 1},   \
      Register{"lock", 47, 1, RW, M, 0, 0, 1}, Register{"punch", 48, 2, RW, M, 0, 0, 1023},     \
      Register{"realtime_tick", 50, 2, R, M, 0, 0, 32767},                                      \
      Register{"current", 68, 2, RW, M, 2048, 0, 4095},                                         \
      Register{"torque_ctrl_mode_enable", 70, 1, RW, M, 0, 0, 1},                               \
      Register{"goal_torque", 71, 2, RW, M, 0, 0, 2047}, Register {                             \
    "goal_acceleration", 73, 1, RW, M, 0, 0, 254                                                \
  }

constexpr std::array kMx64V1 = {STRIDE_MX1_COMMON(mx1::kModelMx64, 160)};
constexpr std::array kMx106V1 = {STRIDE_MX1_COMMON(mx1::kModelMx106, 160),
                                 Register{"drive_mode", 10, 1, RW, E, 0, 0, 3}};
#undef STRIDE_MX1_COMMON

#define STRIDE_MX2_COMMON(model, current_limit, velocity_limit)                                 \
  Register{"model_number", 0, 2, R, E, model, model, model},                                    \
      Register{"model_information", 2, 4, R, E, 0, 0, 0},                                       \
      Register{"firmware_version", 6, 1, R, E, 43, 0, 255},                                     \
      Register{"id", 7, 1, RW, E, 1, 0, 252}, Register{"baud_rate", 8, 1, RW, E, 1, 0, 7},      \
      Register{"return_delay_time", 9, 1, RW, E, 250, 0, 254},                                  \
      Register{"drive_mode", 10, 1, RW, E, 0, 0, 5},                                            \
      Register{"operating_mode", 11, 1, RW, E, 3, 0, 16},                                       \
      Register{"secondary_id", 12, 1, RW, E, 255, 0, 255},                                      \
      Register{"protocol_type", 13, 1, RW, E, 2, 1, 2},                                         \
      Register{"homing_offset", 20, 4, RW, E, 0, 0, 0xFFFFFFFFU},                               \
      Register{"moving_threshold", 24, 4, RW, E, 10, 0, 1023},                                  \
      Register{"temperature_limit", 31, 1, RW, E, 80, 0, 100},                                  \
      Register{"max_voltage_limit", 32, 2, RW, E, 160, 95, 160},                                \
      Register{"min_voltage_limit", 34, 2, RW, E, 95, 95, 160},                                 \
      Register{"pwm_limit", 36, 2, RW, E, 885, 0, 885},                                         \
      Register{"current_limit", 38, 2, RW, E, current_limit, 0, current_limit},                 \
      Register{"acceleration_limit", 40, 4, RW, E, 32767, 0, 32767},                            \
      Register{"velocity_limit", 44, 4, RW, E, velocity_limit, 0, 1023},                        \
      Register{"max_position_limit", 48, 4, RW, E, 4095, 0, 4095},                              \
      Register{"min_position_limit", 52, 4, RW, E, 0, 0, 4095},                                 \
      Register{"shutdown", 63, 1, RW, E, 52, 0, 255},                                           \
      Register{"torque_enable", 64, 1, RW, M, 0, 0, 1}, Register{"led", 65, 1, RW, M, 0, 0, 1}, \
      Register{"status_return_level", 68, 1, RW, M, 2, 0, 2},                                   \
      Register{"registered_instruction", 69, 1, R, M, 0, 0, 1},                                 \
      Register{"hardware_error_status", 70, 1, R, M, 0, 0, 255},                                \
      Register{"velocity_i_gain", 76, 2, RW, M, 1920, 0, 16383},                                \
      Register{"velocity_p_gain", 78, 2, RW, M, 100, 0, 16383},                                 \
      Register{"position_d_gain", 80, 2, RW, M, 0, 0, 16383},                                   \
      Register{"position_i_gain", 82, 2, RW, M, 0, 0, 16383},                                   \
      Register{"position_p_gain", 84, 2, RW, M, 850, 0, 16383},                                 \
      Register{"feedforward_2nd_gain", 88, 2, RW, M, 0, 0, 16383},                              \
      Register{"feedforward_1st_gain", 90, 2, RW, M, 0, 0, 16383},                              \
      Register{"bus_watchdog", 98, 1, RW, M, 0, 0, 127},                                        \
      Register{"goal_pwm", 100, 2, RW, M, 0, 0, 885},                                           \
      Register{"goal_current", 102, 2, RW, M, 0, 0, current_limit},                             \
      Register{"goal_velocity", 104, 4, RW, M, 0, 0, 0xFFFFFFFFU},                              \
      Register{"profile_acceleration", 108, 4, RW, M, 0, 0, 32767},                             \
      Register{"profile_velocity", 112, 4, RW, M, 0, 0, 32767},                                 \
      Register{"goal_position", 116, 4, RW, M, 2048, 0, 4095},                                  \
      Register{"realtime_tick", 120, 2, R, M, 0, 0, 32767},                                     \
      Register{"moving", 122, 1, R, M, 0, 0, 1},                                                \
      Register{"moving_status", 123, 1, R, M, 0, 0, 255},                                       \
      Register{"present_pwm", 124, 2, R, M, 0, 0, 65535},                                       \
      Register{"present_current", 126, 2, R, M, 0, 0, 65535},                                   \
      Register{"present_velocity", 128, 4, R, M, 0, 0, 0xFFFFFFFFU},                            \
      Register{"present_position", 132, 4, R, M, 2048, 0, 0xFFFFFFFFU},                         \
      Register{"velocity_trajectory", 136, 4, R, M, 0, 0, 0xFFFFFFFFU},                         \
      Register{"position_trajectory", 140, 4, R, M, 0, 0, 0xFFFFFFFFU},                         \
      Register{"present_input_voltage", 144, 2, R, M, 150, 0, 65535}, Register {                \
    "present_temperature", 146, 1, R, M, 35, 0, 255                                             \
  }

constexpr std::array kMx64V2 = {STRIDE_MX2_COMMON(mx2::kModelMx64, 1941, 435)};
constexpr std::array kMx106V2 = {STRIDE_MX2_COMMON(mx2::kModelMx106, 2047, 360)};
#undef STRIDE_MX2_COMMON

constexpr std::array kCm730 = {
    Register{"model_number", 0, 2, R, E, cm730::kModel, cm730::kModel, cm730::kModel},
    Register{"firmware_version", 2, 1, R, E, 16, 0, 255},
    Register{"id", 3, 1, RW, E, 200, 0, 253},
    Register{"baud_rate", 4, 1, RW, E, 1, 0, 254},
    Register{"return_delay_time", 5, 1, RW, E, 0, 0, 254},
    Register{"status_return_level", 16, 1, RW, E, 2, 0, 2},
    Register{"dynamixel_power", 24, 1, RW, M, 0, 0, 1},
    Register{"led_panel", 25, 1, RW, M, 0, 0, 7},
    Register{"led_head", 26, 2, RW, M, 0, 0, 32767},
    Register{"led_eye", 28, 2, RW, M, 0, 0, 32767},
    Register{"button", 30, 1, R, M, 0, 0, 3},
    Register{"gyro_z", 38, 2, R, M, 512, 0, 1023},
    Register{"gyro_y", 40, 2, R, M, 512, 0, 1023},
    Register{"gyro_x", 42, 2, R, M, 512, 0, 1023},
    Register{"accel_x", 44, 2, R, M, 512, 0, 1023},
    Register{"accel_y", 46, 2, R, M, 512, 0, 1023},
    Register{"accel_z", 48, 2, R, M, 640, 0, 1023},
    Register{"present_voltage", 50, 1, R, M, 150, 0, 255},
};

// NimbRo's CM730 (igus.md 6.5). The IMU registers are signed 16-bit values (two's complement in
// the register's 0..65535); upright and still the accelerometer's z reads +1 g = 8192 LSB (65536 /
// 8).
constexpr std::array kCm730Nimbro = {
    Register{"model_number", 0, 2, R, E, cm730_nimbro::kModel, cm730_nimbro::kModel,
             cm730_nimbro::kModel},
    Register{"firmware_version", 2, 1, R, E, 16, 0, 255},
    Register{"id", 3, 1, RW, E, 200, 0, 253},
    Register{"baud_rate", 4, 1, RW, E, 1, 0, 254},
    Register{"return_delay_time", 5, 1, RW, E, 0, 0, 254},
    Register{"status_return_level", 16, 1, RW, E, 2, 0, 2},
    Register{"dynamixel_power", 24, 1, RW, M, 0, 0, 1},
    Register{"led_panel", 25, 1, RW, M, 0, 0, 7},
    Register{"rgbled5", 26, 2, RW, M, 0, 0, 32767},
    Register{"rgbled6", 28, 2, RW, M, 0, 0, 32767},
    Register{"button", 30, 1, R, M, 0, 0, 3},
    Register{"battery_voltage", 31, 1, R, M, 150, 0, 255},
    Register{"gyro_x", 32, 2, R, M, 0, 0, 65535},
    Register{"gyro_y", 34, 2, R, M, 0, 0, 65535},
    Register{"gyro_z", 36, 2, R, M, 0, 0, 65535},
    Register{"acc_x", 38, 2, R, M, 0, 0, 65535},
    Register{"acc_y", 40, 2, R, M, 0, 0, 65535},
    Register{"acc_z", 42, 2, R, M, 8192, 0, 65535},
    Register{"mag_x", 44, 2, R, M, 0, 0, 65535},
    Register{"mag_y", 46, 2, R, M, 0, 0, 65535},
    Register{"mag_z", 48, 2, R, M, 0, 0, 65535},
    Register{"temperature", 50, 1, R, M, 35, 0, 255},
};

const ControlTable kMx64V1Table{"MX-64", mx1::kModelMx64, Protocol::kV1, mx1::kTableSize, kMx64V1};
const ControlTable kMx106V1Table{"MX-106", mx1::kModelMx106, Protocol::kV1, mx1::kTableSize,
                                 kMx106V1};
const ControlTable kMx64V2Table{"MX-64(2.0)", mx2::kModelMx64, Protocol::kV2, mx2::kTableSize,
                                kMx64V2};
const ControlTable kMx106V2Table{"MX-106(2.0)", mx2::kModelMx106, Protocol::kV2, mx2::kTableSize,
                                 kMx106V2};
const ControlTable kCm730Table{"CM730", cm730::kModel, Protocol::kV1, cm730::kTableSize, kCm730};
const ControlTable kCm730NimbroTable{"CM730 (NimbRo firmware)", cm730_nimbro::kModel, Protocol::kV1,
                                     cm730_nimbro::kTableSize, kCm730Nimbro};

}  // namespace

const Register* ControlTable::find(std::string_view name) const {
  for (const Register& r : registers) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

const Register* ControlTable::at(std::uint16_t address) const {
  for (const Register& r : registers) {
    if (r.address == address) return &r;
  }
  return nullptr;
}

const Register* ControlTable::covering(std::uint16_t address) const {
  for (const Register& r : registers) {
    if (address >= r.address && address < r.address + r.size) return &r;
  }
  return nullptr;
}

const ControlTable& mx64_v1_table() {
  return kMx64V1Table;
}
const ControlTable& mx106_v1_table() {
  return kMx106V1Table;
}
const ControlTable& mx64_v2_table() {
  return kMx64V2Table;
}
const ControlTable& mx106_v2_table() {
  return kMx106V2Table;
}
const ControlTable& cm730_table() {
  return kCm730Table;
}

const ControlTable& cm730_nimbro_table() {
  return kCm730NimbroTable;
}

const char* to_string(Cm730Profile profile) {
  return profile == Cm730Profile::kNimbro ? "nimbro" : "stock";
}

bool parse_cm730_profile(std::string_view text, Cm730Profile& out) {
  if (text == "stock") {
    out = Cm730Profile::kStock;
  } else if (text == "nimbro") {
    out = Cm730Profile::kNimbro;
  } else {
    return false;
  }
  return true;
}

const ControlTable& cm730_table(Cm730Profile profile) {
  return profile == Cm730Profile::kNimbro ? kCm730NimbroTable : kCm730Table;
}

const ControlTable* table_for_model(std::uint16_t model_number, Protocol protocol) {
  for (const ControlTable* t : {&kMx64V1Table, &kMx106V1Table, &kMx64V2Table, &kMx106V2Table,
                                &kCm730Table, &kCm730NimbroTable}) {
    if (t->model_number == model_number && t->protocol == protocol) return t;
  }
  return nullptr;
}

}  // namespace stride::hal::dxl
