// Conversions between Dynamixel register values and SI units (igus.md sections 1.5, 6.2-6.4).
//
// Position (MX, 4096 ticks per revolution, centre 2048), with the servo table's direction d and
// zero offset o:   ticks = d * (angle - o) * 4096 / (2 pi) + 2048.
// Stride uses 4096 ticks/rev (the AS5045 encoder's resolution), not NUbots' 4095
// (firmware/config/servo_table.json). Writes wrap (angle - o) into [-pi, pi) first, so a joint
// angle and the same angle +- 2 pi give the same ticks; reads return an angle in [-pi, pi).
//
// Speeds: MX 1.0 moving/present speed unit 0.114 rpm (0.011938 rad/s); present speed and
// load carry their direction in bit 10 (set = CW = negative ticks direction). MX 2.0 velocity
// unit 0.229 rpm. Gains: Kp = P/8, Ki = I*1000/2048, Kd = D*4/1000 (1.0 firmware);
// K_PP = P/128, K_PI = I/65536, K_PD = D/16 (2.0 firmware). CM730 IMU: accel
// (raw - 512) * 4 g / 512, gyro (raw - 512) * 1800 deg/s / 512 (as NUbots converts it).
// CM730 with NimbRo's firmware (igus.md 6.5, humanoid_op_ros cm730 driver): signed 16-bit
// registers, gyro (pi/180) 500/65536 rad/s per LSB (+-250 deg/s), accel 2*4*9.81/65536 m/s^2
// per LSB (+-4 g), magnetometer 1/820 gauss per LSB.
#pragma once

#include <cstdint>

namespace stride::hal::dxl {

enum class ServoModelId : std::uint8_t { kMx64, kMx106 };

/// Per-servo conversion parameters (filled by the firmware from its ServoTable).
struct ServoCalibration {
  int direction = 1;        ///< +1 or -1: servo sense relative to the URDF joint axis
  double offset_rad = 0.0;  ///< URDF angle at which the servo reads 2048
  ServoModelId model = ServoModelId::kMx106;
};

/// Protocol 1.0 model number (310 MX-64, 320 MX-106).
std::uint16_t model_number_v1(ServoModelId model);
/// No-load speed at 14.8 V [rad/s] (MX-64 78 rpm, MX-106 55 rpm; igus.md 6.1).
double no_load_speed_rad_s(ServoModelId model);

namespace units {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTicksPerRev = 4096.0;
inline constexpr double kCentreTick = 2048.0;
inline constexpr double kRadPerTick = 2.0 * kPi / kTicksPerRev;
/// MX 1.0 moving/present speed unit: 0.114 rpm [rad/s].
inline constexpr double kSpeedUnitRadS = 0.114 * 2.0 * kPi / 60.0;
/// MX 2.0 velocity unit: 0.229 rpm [rad/s].
inline constexpr double kV2VelocityUnitRadS = 0.229 * 2.0 * kPi / 60.0;
inline constexpr double kStandardGravity = 9.80665;
inline constexpr double kAccelPerLsb = 4.0 * kStandardGravity / 512.0;  ///< [m/s^2]
inline constexpr double kGyroPerLsb = 1800.0 * kPi / 180.0 / 512.0;     ///< [rad/s]

/// Goal position register for a URDF joint angle (clamped to 0..4095).
std::uint16_t position_to_ticks(double angle_rad, const ServoCalibration& cal);
/// URDF joint angle in [-pi, pi) for a position register value.
double ticks_to_position(std::uint16_t ticks, const ServoCalibration& cal);

/// Moving speed register for a speed limit [rad/s]: 0 (or <= 0, or not finite) = no limit;
/// otherwise at least 1 (never rounded to 0, which would mean full speed), at most 1023.
std::uint16_t moving_speed_to_register(double speed_rad_s);
/// Speed limit [rad/s] of a moving speed register (0 -> 0 = no limit).
double moving_speed_from_register(std::uint16_t value);

/// Signed 1.0 value with direction bit 10 (present speed, present load) -> signed count.
int signed_from_bit10(std::uint16_t value);
/// Signed count -> 1.0 value with direction bit 10 (magnitude clamped to 1023).
std::uint16_t bit10_from_signed(int value);

/// Present speed register -> joint speed [rad/s] (direction applied).
double present_speed_from_register(std::uint16_t value, const ServoCalibration& cal);
/// Joint speed [rad/s] -> present speed register (direction applied).
std::uint16_t present_speed_to_register(double speed_rad_s, const ServoCalibration& cal);
/// Present load register -> signed fraction of max torque in the joint's sense [-1, 1].
double load_from_register(std::uint16_t value, const ServoCalibration& cal);
std::uint16_t load_to_register(double load, const ServoCalibration& cal);

/// Torque limit fraction [0, 1] <-> register 0..1023.
std::uint16_t torque_limit_to_register(double fraction);
double torque_limit_from_register(std::uint16_t value);

/// Gain register value (P, I or D in 1.0 units) clamped and rounded to 0..254.
std::uint8_t gain_to_register(double gain);
/// The scripts' 0-100 gain g -> P register = round(2.54 g) (igus.md 6.4).
std::uint8_t script_gain_to_register(double g);
double kp_from_p_register(double p);  ///< Kp = P / 8
double ki_from_i_register(double i);  ///< Ki = I * 1000 / 2048
double kd_from_d_register(double d);  ///< Kd = D * 4 / 1000

/// 2.0 firmware gains.
double v2_kpp_from_register(double p);  ///< K_PP = P / 128
double v2_kpi_from_register(double i);  ///< K_PI = I / 65536
double v2_kpd_from_register(double d);  ///< K_PD = D / 16
/// 2.0 profile velocity / present velocity (0.229 rpm) <-> rad/s.
std::uint32_t v2_velocity_to_register(double speed_rad_s);
double v2_velocity_from_register(std::uint32_t value);

double voltage_from_register(std::uint8_t value);  ///< 0.1 V units
std::uint8_t voltage_to_register(double volts);
double temperature_from_register(std::uint8_t value);  ///< deg C
std::uint8_t temperature_to_register(double celsius);

/// CM730 IMU raw (10-bit, centre 512) <-> m/s^2 and rad/s.
double accel_from_raw(std::uint16_t raw);
std::uint16_t accel_to_raw(double mps2);
double gyro_from_raw(std::uint16_t raw);
std::uint16_t gyro_to_raw(double rad_s);

/// CM730 with NimbRo's firmware: signed 16-bit registers (igus.md 6.5).
inline constexpr double kNimbroGyroPerLsb = kPi / 180.0 * 500.0 / 65536.0;  ///< [rad/s]
inline constexpr double kNimbroAccelPerLsb = 2.0 * 4.0 * 9.81 / 65536.0;    ///< [m/s^2]
inline constexpr double kNimbroMagPerLsb = 1.0 / 820.0;                     ///< [gauss]
/// Register (two's complement 16 bits) -> SI; SI -> register, rounded and clamped to
/// -32768..32767 (a non-finite value reads 0).
double nimbro_gyro_from_raw(std::uint16_t raw);
std::uint16_t nimbro_gyro_to_raw(double rad_s);
double nimbro_accel_from_raw(std::uint16_t raw);
std::uint16_t nimbro_accel_to_raw(double mps2);
double nimbro_mag_from_raw(std::uint16_t raw);
std::uint16_t nimbro_mag_to_raw(double gauss);

}  // namespace units
}  // namespace stride::hal::dxl
