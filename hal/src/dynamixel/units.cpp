// Register <-> SI conversions (see units.hpp for the formulas and their sources).
#include "stride/hal/dynamixel/units.hpp"

#include <algorithm>
#include <cmath>

namespace stride::hal::dxl {

std::uint16_t model_number_v1(ServoModelId model) {
  return model == ServoModelId::kMx64 ? 310 : 320;
}

double no_load_speed_rad_s(ServoModelId model) {
  const double rpm = model == ServoModelId::kMx64 ? 78.0 : 55.0;
  return rpm * 2.0 * units::kPi / 60.0;
}

namespace units {

namespace {
double wrap_pi(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a < 0.0) a += 2.0 * kPi;
  return a - kPi;
}
template <typename T>
T clamp_round(double v, double lo, double hi) {
  if (!std::isfinite(v)) return static_cast<T>(lo);
  return static_cast<T>(std::lround(std::clamp(v, lo, hi)));
}
}  // namespace

std::uint16_t position_to_ticks(double angle_rad, const ServoCalibration& cal) {
  if (!std::isfinite(angle_rad)) return static_cast<std::uint16_t>(kCentreTick);
  const double relative = wrap_pi(angle_rad - cal.offset_rad);
  return clamp_round<std::uint16_t>(cal.direction * relative / kRadPerTick + kCentreTick, 0.0,
                                    4095.0);
}

double ticks_to_position(std::uint16_t ticks, const ServoCalibration& cal) {
  const double relative = cal.direction * (static_cast<double>(ticks) - kCentreTick) * kRadPerTick;
  return wrap_pi(relative + cal.offset_rad);
}

std::uint16_t moving_speed_to_register(double speed_rad_s) {
  if (!std::isfinite(speed_rad_s) || speed_rad_s <= 0.0) return 0;
  return clamp_round<std::uint16_t>(speed_rad_s / kSpeedUnitRadS, 1.0, 1023.0);
}

double moving_speed_from_register(std::uint16_t value) {
  return static_cast<double>(value & 0x3FFU) * kSpeedUnitRadS;
}

int signed_from_bit10(std::uint16_t value) {
  const int magnitude = value & 0x3FF;
  return (value & 0x400U) != 0 ? -magnitude : magnitude;
}

std::uint16_t bit10_from_signed(int value) {
  const int magnitude = std::min(std::abs(value), 1023);
  return static_cast<std::uint16_t>(value < 0 ? (magnitude | 0x400) : magnitude);
}

double present_speed_from_register(std::uint16_t value, const ServoCalibration& cal) {
  return cal.direction * signed_from_bit10(value) * kSpeedUnitRadS;
}

std::uint16_t present_speed_to_register(double speed_rad_s, const ServoCalibration& cal) {
  if (!std::isfinite(speed_rad_s)) return 0;
  return bit10_from_signed(static_cast<int>(
      std::lround(std::clamp(cal.direction * speed_rad_s / kSpeedUnitRadS, -1023.0, 1023.0))));
}

double load_from_register(std::uint16_t value, const ServoCalibration& cal) {
  return cal.direction * signed_from_bit10(value) / 1023.0;
}

std::uint16_t load_to_register(double load, const ServoCalibration& cal) {
  if (!std::isfinite(load)) return 0;
  return bit10_from_signed(
      static_cast<int>(std::lround(std::clamp(cal.direction * load, -1.0, 1.0) * 1023.0)));
}

std::uint16_t torque_limit_to_register(double fraction) {
  return clamp_round<std::uint16_t>(fraction * 1023.0, 0.0, 1023.0);
}

double torque_limit_from_register(std::uint16_t value) {
  return std::min<double>(value, 1023.0) / 1023.0;
}

std::uint8_t gain_to_register(double gain) {
  return clamp_round<std::uint8_t>(gain, 0.0, 254.0);
}
std::uint8_t script_gain_to_register(double g) {
  return gain_to_register(2.54 * g);
}
double kp_from_p_register(double p) {
  return p / 8.0;
}
double ki_from_i_register(double i) {
  return i * 1000.0 / 2048.0;
}
double kd_from_d_register(double d) {
  return d * 4.0 / 1000.0;
}
double v2_kpp_from_register(double p) {
  return p / 128.0;
}
double v2_kpi_from_register(double i) {
  return i / 65536.0;
}
double v2_kpd_from_register(double d) {
  return d / 16.0;
}

std::uint32_t v2_velocity_to_register(double speed_rad_s) {
  if (!std::isfinite(speed_rad_s) || speed_rad_s <= 0.0) return 0;
  return clamp_round<std::uint32_t>(speed_rad_s / kV2VelocityUnitRadS, 1.0, 32767.0);
}

double v2_velocity_from_register(std::uint32_t value) {
  return static_cast<double>(static_cast<std::int32_t>(value)) * kV2VelocityUnitRadS;
}

double voltage_from_register(std::uint8_t value) {
  return value * 0.1;
}
std::uint8_t voltage_to_register(double volts) {
  return clamp_round<std::uint8_t>(volts * 10.0, 0.0, 255.0);
}
double temperature_from_register(std::uint8_t value) {
  return value;
}
std::uint8_t temperature_to_register(double celsius) {
  return clamp_round<std::uint8_t>(celsius, 0.0, 255.0);
}

double accel_from_raw(std::uint16_t raw) {
  return (static_cast<double>(raw) - 512.0) * kAccelPerLsb;
}
std::uint16_t accel_to_raw(double mps2) {
  return clamp_round<std::uint16_t>(mps2 / kAccelPerLsb + 512.0, 0.0, 1023.0);
}
double gyro_from_raw(std::uint16_t raw) {
  return (static_cast<double>(raw) - 512.0) * kGyroPerLsb;
}
std::uint16_t gyro_to_raw(double rad_s) {
  return clamp_round<std::uint16_t>(rad_s / kGyroPerLsb + 512.0, 0.0, 1023.0);
}

namespace {
double from_signed16(std::uint16_t raw, double lsb) {
  return static_cast<double>(static_cast<std::int16_t>(raw)) * lsb;
}
std::uint16_t to_signed16(double value, double lsb) {
  if (!std::isfinite(value)) return 0;
  const auto count =
      static_cast<std::int16_t>(std::lround(std::clamp(value / lsb, -32768.0, 32767.0)));
  return static_cast<std::uint16_t>(count);
}
}  // namespace

double nimbro_gyro_from_raw(std::uint16_t raw) {
  return from_signed16(raw, kNimbroGyroPerLsb);
}
std::uint16_t nimbro_gyro_to_raw(double rad_s) {
  return to_signed16(rad_s, kNimbroGyroPerLsb);
}
double nimbro_accel_from_raw(std::uint16_t raw) {
  return from_signed16(raw, kNimbroAccelPerLsb);
}
std::uint16_t nimbro_accel_to_raw(double mps2) {
  return to_signed16(mps2, kNimbroAccelPerLsb);
}
double nimbro_mag_from_raw(std::uint16_t raw) {
  return from_signed16(raw, kNimbroMagPerLsb);
}
std::uint16_t nimbro_mag_to_raw(double gauss) {
  return to_signed16(gauss, kNimbroMagPerLsb);
}

}  // namespace units
}  // namespace stride::hal::dxl
