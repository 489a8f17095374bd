// The protocol 2.0 emulated MX(2.0) servos: PING, READ/WRITE with the 2.0 error field,
// SYNC_READ/SYNC_WRITE/BULK_READ, REBOOT, CRC errors, lockstep motion, overheating alert.
#include <gtest/gtest.h>

#include <array>

#include "dxl_test_util.hpp"
#include "stride/firmware/dynamixel_config.hpp"
#include "stride/hal/dynamixel/codec_v2.hpp"
#include "stride/hal/dynamixel/virtual_bus_v2.hpp"

namespace stride::hal::dxl {
namespace {

using test::Bytes;

struct BenchV2 {
  BenchV2() {
    VirtualBusV2::Options options;
    options.calibration = fw::servo_calibrations(fw::ServoTable::defaults());
    options.lockstep = true;
    options.overheat[13] = true;
    FirstOrderPhysics::Options physics;
    for (std::size_t i = 0; i < kServoCount; ++i) physics.models[i] = options.calibration[i].model;
    bus = std::make_unique<VirtualBusV2>(options, std::make_unique<FirstOrderPhysics>(physics));
  }
  template <typename F>
  std::vector<Packet> call(F encode) {
    Bytes b(1100);
    b.resize(encode(std::span<std::uint8_t>(b)));
    return send(b);
  }
  std::vector<Packet> send(const Bytes& b) {
    std::vector<std::uint8_t> out;
    std::int64_t delay = 0;
    bus->receive(b, out, delay);
    return test::parse_all(Protocol::kV2, PacketParser::Role::kHost, out);
  }
  std::unique_ptr<VirtualBusV2> bus;
};

TEST(VirtualBusV2, PingReportsModelAndBroadcastPingEveryServo) {
  BenchV2 b;
  auto r = b.call([](auto s) { return v2::encode_ping(s, 7); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(read_u16(r[0].params.data()), mx2::kModelMx106);
  r = b.call([](auto s) { return v2::encode_ping(s, 1); });
  EXPECT_EQ(read_u16(r[0].params.data()), mx2::kModelMx64);
  r = b.call([](auto s) { return v2::encode_ping(s, kBroadcastId); });
  ASSERT_EQ(r.size(), 20U);
  EXPECT_EQ(r[19].id, 20);
}

TEST(VirtualBusV2, WriteErrorsAndMotion) {
  BenchV2 b;
  const std::array<std::uint8_t, 4> goal{0xB8, 0x0B, 0, 0};  // 3000
  auto r = b.call([&](auto s) { return v2::encode_write(s, 9, mx2::kGoalPosition, goal); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].error, 0);
  const std::array<std::uint8_t, 1> on{1};
  (void)b.call([&](auto s) { return v2::encode_write(s, 9, mx2::kTorqueEnable, on); });
  // EEPROM while torque is on: access error; read-only register: access error; out of range.
  const std::array<std::uint8_t, 1> baud{3};
  r = b.call([&](auto s) { return v2::encode_write(s, 9, 8, baud); });
  EXPECT_EQ(r[0].error, v2_error::kAccess);
  r = b.call([&](auto s) { return v2::encode_write(s, 9, mx2::kPresentTemperature, baud); });
  EXPECT_EQ(r[0].error, v2_error::kAccess);
  const std::array<std::uint8_t, 4> too_far{0x00, 0x20, 0, 0};  // 8192 > 4095
  r = b.call([&](auto s) { return v2::encode_write(s, 9, mx2::kGoalPosition, too_far); });
  EXPECT_EQ(r[0].error, v2_error::kDataRange);
  EXPECT_EQ(b.bus->peek(9, mx2::kGoalPosition, 4), 3000U);
  r = b.call([](auto s) { return v2::encode_instruction(s, 9, 0x44, {}); });
  EXPECT_EQ(r[0].error, v2_error::kInstruction);
  // Lockstep: each SYNC_READ is one 10 ms tick; after 1 s the servo is at its goal.
  const std::array<std::uint8_t, 2> ids{9, 10};
  for (int tick = 0; tick < 100; ++tick) {
    r = b.call([&](auto s) { return v2::encode_sync_read(s, mx2::kPresentPosition, 4, ids); });
  }
  ASSERT_EQ(r.size(), 2U);
  EXPECT_NEAR(static_cast<double>(read_u32(r[0].params.data())), 3000.0, 3.0);
  EXPECT_EQ(read_u32(r[1].params.data()), 2048U);  // servo 10 never moved
  // BULK_READ of different registers; SYNC_WRITE.
  const Bytes records{1, 0x00, 0x04, 0, 0, 2, 0x00, 0x04, 0, 0};
  (void)b.call([&](auto s) { return v2::encode_sync_write(s, mx2::kGoalPosition, 4, records); });
  EXPECT_EQ(b.bus->peek(2, mx2::kGoalPosition, 4), 1024U);
  const std::array<BulkReadEntry, 2> entries{BulkReadEntry{2, mx2::kGoalPosition, 4},
                                             BulkReadEntry{5, mx2::kPresentTemperature, 1}};
  r = b.call([&](auto s) { return v2::encode_bulk_read(s, entries); });
  ASSERT_EQ(r.size(), 2U);
  EXPECT_EQ(read_u32(r[0].params.data()), 1024U);
  EXPECT_EQ(r[1].param_count, 1);
  // REBOOT restores RAM (goal position back to the present position, torque off).
  r = b.call([](auto s) { return v2::encode_reboot(s, 9); });
  EXPECT_EQ(b.bus->peek(9, mx2::kTorqueEnable, 1), 0U);
}

TEST(VirtualBusV2, OverheatingSetsTheAlertBitAndCrcErrorsAreAnswered) {
  BenchV2 b;
  auto r = b.call([](auto s) { return v2::encode_read(s, 13, mx2::kHardwareErrorStatus, 1); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_NE(r[0].error & v2_error::kAlert, 0);
  EXPECT_EQ(r[0].params[0], 0x04);
  Bytes bad(64);
  bad.resize(v2::encode_ping(bad, 4));
  bad.back() ^= 0x11;
  r = b.send(bad);
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].id, 4);
  EXPECT_EQ(r[0].error, v2_error::kCrc);
}

}  // namespace
}  // namespace stride::hal::dxl
