// Flight log byte format: tick encoding and decoding, CRC-32, little-endian helpers.
#include "stride/firmware/recorder/flight_log_format.hpp"

#include <bit>
#include <cstring>

namespace stride::fw::flight_log {

namespace {

// Sequential little-endian writer/reader over a byte buffer whose size the caller checked.
struct Writer {
  std::uint8_t* at;
  template <typename U>
  void uint(U value) noexcept {
    for (std::size_t i = 0; i < sizeof(U); ++i) *at++ = static_cast<std::uint8_t>(value >> (8 * i));
  }
  void u8(std::uint8_t value) noexcept { *at++ = value; }
  void f32(double value) noexcept { uint(std::bit_cast<std::uint32_t>(static_cast<float>(value))); }
  void f64(double value) noexcept { uint(std::bit_cast<std::uint64_t>(value)); }
  void i64(std::int64_t value) noexcept { uint(static_cast<std::uint64_t>(value)); }
};

struct Reader {
  const std::uint8_t* at;
  template <typename U>
  U uint() noexcept {
    U value = 0;
    for (std::size_t i = 0; i < sizeof(U); ++i) value |= static_cast<U>(U{*at++} << (8 * i));
    return value;
  }
  std::uint8_t u8() noexcept { return *at++; }
  double f32() noexcept { return std::bit_cast<float>(uint<std::uint32_t>()); }
  double f64() noexcept { return std::bit_cast<double>(uint<std::uint64_t>()); }
  std::int64_t i64() noexcept { return static_cast<std::int64_t>(uint<std::uint64_t>()); }
};

constexpr std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1U) != 0 ? 0xEDB88320U ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}
constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

constexpr std::uint8_t kHealthMask = 0x03;
constexpr std::uint8_t kTorqueEnabledBit = 0x04;
constexpr std::uint8_t kFallenBit = 0x01;

}  // namespace

std::size_t encode_tick(const TickMeta& meta, const hal::SensorFrame& sensors,
                        const hal::CommandFrame& commands, const ParamChange* changes,
                        std::size_t change_count, std::uint8_t* out) noexcept {
  Writer w{out};
  w.i64(meta.tick);
  w.i64(sensors.tick);
  w.i64(commands.tick);
  w.uint(meta.dropped_before);
  w.u8(static_cast<std::uint8_t>(meta.motion));
  w.u8(meta.fallen ? kFallenBit : 0);
  w.uint(static_cast<std::uint16_t>(change_count));
  w.f32(meta.tilt_rad);
  for (const hal::ServoState& s : sensors.servos) {
    for (double v : {s.position_rad, s.speed_rad_s, s.load, s.voltage_v, s.temperature_c,
                     s.goal_position_rad, s.p_gain, s.i_gain, s.d_gain, s.torque_limit}) {
      w.f32(v);
    }
    w.u8(s.error_flags);
    w.u8(static_cast<std::uint8_t>((static_cast<std::uint8_t>(s.health) & kHealthMask) |
                                   (s.torque_enabled ? kTorqueEnabledBit : 0)));
  }
  const hal::Cm730State& cm = sensors.cm730;
  for (double v : cm.accel_mps2) w.f32(v);
  for (double v : cm.gyro_rad_s) w.f32(v);
  w.f32(cm.voltage_v);
  w.u8(cm.buttons);
  w.u8(cm.error_flags);
  w.u8(static_cast<std::uint8_t>(cm.health));
  for (const hal::ServoCommand& c : commands.servos) {
    for (double v :
         {c.position_rad, c.moving_speed_rad_s, c.p_gain, c.i_gain, c.d_gain, c.torque_limit}) {
      w.f32(v);
    }
    w.u8(c.torque_enable ? 1 : 0);
  }
  for (std::size_t i = 0; i < change_count; ++i) {
    w.uint(static_cast<std::uint16_t>(changes[i].handle));
    w.f64(changes[i].value);
  }
  return static_cast<std::size_t>(w.at - out);
}

bool decode_tick(const std::uint8_t* payload, std::size_t size, TickMeta& meta,
                 hal::SensorFrame& sensors, hal::CommandFrame& commands,
                 std::size_t& change_count) noexcept {
  if (size < kTickFixedBytes) return false;
  Reader r{payload};
  meta.tick = r.i64();
  sensors.tick = r.i64();
  commands.tick = r.i64();
  meta.dropped_before = r.uint<std::uint32_t>();
  meta.motion = static_cast<MotionState>(r.u8());
  meta.fallen = (r.u8() & kFallenBit) != 0;
  change_count = r.uint<std::uint16_t>();
  meta.tilt_rad = static_cast<float>(r.f32());
  if (size != kTickFixedBytes + change_count * kParamChangeBytes) return false;
  for (hal::ServoState& s : sensors.servos) {
    for (double* v : {&s.position_rad, &s.speed_rad_s, &s.load, &s.voltage_v, &s.temperature_c,
                      &s.goal_position_rad, &s.p_gain, &s.i_gain, &s.d_gain, &s.torque_limit}) {
      *v = r.f32();
    }
    s.error_flags = r.u8();
    const std::uint8_t status = r.u8();
    s.health = static_cast<hal::DeviceHealth>(status & kHealthMask);
    s.torque_enabled = (status & kTorqueEnabledBit) != 0;
  }
  hal::Cm730State& cm = sensors.cm730;
  for (double& v : cm.accel_mps2) v = r.f32();
  for (double& v : cm.gyro_rad_s) v = r.f32();
  cm.voltage_v = r.f32();
  cm.buttons = r.u8();
  cm.error_flags = r.u8();
  cm.health = static_cast<hal::DeviceHealth>(r.u8() & kHealthMask);
  for (hal::ServoCommand& c : commands.servos) {
    for (double* v : {&c.position_rad, &c.moving_speed_rad_s, &c.p_gain, &c.i_gain, &c.d_gain,
                      &c.torque_limit}) {
      *v = r.f32();
    }
    c.torque_enable = r.u8() != 0;
  }
  return true;
}

ParamChange decode_param_change(const std::uint8_t* payload, std::size_t index) noexcept {
  Reader r{payload + kTickFixedBytes + index * kParamChangeBytes};
  ParamChange change;
  change.handle = r.uint<std::uint16_t>();
  change.value = r.f64();
  return change;
}

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc) noexcept {
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = kCrcTable[(crc ^ data[i]) & 0xFFU] ^ (crc >> 8);
  return ~crc;
}

void put_u32(std::uint8_t* out, std::uint32_t value) noexcept {
  Writer{out}.uint(value);
}

std::uint32_t get_u32(const std::uint8_t* in) noexcept {
  return Reader{in}.uint<std::uint32_t>();
}

}  // namespace stride::fw::flight_log
