// The flight log's byte format (firmware/src/recorder/FLIGHT_LOG.md): the file magic, the
// block framing (length, type, payload, CRC-32) and the fixed little-endian layout of one tick
// record. Shared by the recorder that writes logs and the reader that reads them back.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "stride/firmware/motion_manager.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/hal/command_frame.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw::flight_log {

/// First 8 bytes of every flight log, then the u32 format version and a u32 of zero.
inline constexpr std::array<char, 8> kMagic{'S', 'T', 'R', 'I', 'D', 'E', 'F', 'L'};
inline constexpr std::uint32_t kFormatVersion = 1;
inline constexpr std::size_t kFileHeadBytes = 16;

/// Block framing: u32 payload length, u32 type, payload, u32 CRC-32 (IEEE, as zlib.crc32) of
/// the 8 head bytes and the payload.
inline constexpr std::size_t kBlockHeadBytes = 8;
inline constexpr std::size_t kBlockTailBytes = 4;
/// A length above this is corruption (a tick is about 1.4 kB, the header some 40 kB).
inline constexpr std::uint32_t kMaxPayloadBytes = 64U << 20;

enum class BlockType : std::uint32_t {
  kHeader = 1,  ///< UTF-8 JSON: firmware, servo table, parameters at start, description hash
  kTick = 2,    ///< one control cycle (layout below)
  kEnd = 3,     ///< UTF-8 JSON: totals, written when stride-fw stops cleanly
};

/// Tick payload: fixed part, then `param_change_count` changes of kParamChangeBytes each.
inline constexpr std::size_t kServoSensorBytes = 10 * 4 + 2;  // 42
inline constexpr std::size_t kCm730Bytes = 7 * 4 + 3;         // 31
inline constexpr std::size_t kServoCommandBytes = 6 * 4 + 1;  // 25
inline constexpr std::size_t kTickPrefixBytes = 36;           // ticks, motion
inline constexpr std::size_t kTickFixedBytes = kTickPrefixBytes +
                                               hal::kServoCount * kServoSensorBytes + kCm730Bytes +
                                               hal::kServoCount * kServoCommandBytes;
inline constexpr std::size_t kParamChangeBytes = 2 + 8;  // u16 parameter index, f64 value

/// One parameter change applied at the start of a tick: index into the header's parameter
/// list (the ParameterStore handle) and the new value.
struct ParamChange {
  ParamHandle handle = 0;
  double value = 0.0;
};

/// What the recorder knows about a tick besides the frames.
struct TickMeta {
  hal::Tick tick = 0;                ///< the loop's tick
  std::uint32_t dropped_before = 0;  ///< ticks the recorder dropped since the previous record
  MotionState motion = MotionState::kStand;
  bool fallen = false;    ///< safety layer's fall state after this tick's step
  float tilt_rad = 0.0F;  ///< safety layer's filtered torso tilt
};

/// Encodes one tick into `out` (at least kTickFixedBytes + n * kParamChangeBytes bytes);
/// returns the bytes written. Real-time: no allocation.
std::size_t encode_tick(const TickMeta& meta, const hal::SensorFrame& sensors,
                        const hal::CommandFrame& commands, const ParamChange* changes,
                        std::size_t change_count, std::uint8_t* out) noexcept;

/// Decodes the fixed part of a tick payload of `size` bytes; returns false if it is too short
/// or its change count does not match its size. Values come back as the float32 written.
bool decode_tick(const std::uint8_t* payload, std::size_t size, TickMeta& meta,
                 hal::SensorFrame& sensors, hal::CommandFrame& commands,
                 std::size_t& change_count) noexcept;
/// The i-th parameter change of a tick payload that decode_tick accepted.
ParamChange decode_param_change(const std::uint8_t* payload, std::size_t index) noexcept;

/// CRC-32 (IEEE 802.3, reflected, as zlib.crc32), continuing from `crc` (0 to start).
std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0) noexcept;

/// Little-endian stores and loads.
void put_u32(std::uint8_t* out, std::uint32_t value) noexcept;
std::uint32_t get_u32(const std::uint8_t* in) noexcept;

}  // namespace stride::fw::flight_log
