// The protocol 2.0 emulated MX(2.0) servos: PING, READ/WRITE with the 2.0 error field,
// SYNC_READ/SYNC_WRITE/BULK_READ, REBOOT, CRC errors, lockstep motion, overheating alert, the
// bus counters and injected faults.
#include <gtest/gtest.h>

#include <array>

#include "bench_v2.hpp"

namespace stride::hal::dxl {
namespace {

using test::BenchV2;
using test::Bytes;

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

TEST(VirtualBusV2, CountsRequestsRepliesAndErrors) {
  BenchV2 b;
  (void)b.call([](auto s) { return v2::encode_ping(s, 1); });
  const std::array<std::uint8_t, 1> one{1};
  auto r = b.call([&](auto s) { return v2::encode_write(s, 2, mx2::kPresentTemperature, one); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].error, v2_error::kAccess);
  const std::array<std::uint8_t, 3> ids{1, 2, 3};
  EXPECT_EQ(
      b.call([&](auto s) { return v2::encode_sync_read(s, mx2::kGoalPosition, 4, ids); }).size(),
      3U);
  const std::array<BulkReadEntry, 1> entries{BulkReadEntry{4, mx2::kGoalPosition, 4}};
  (void)b.call([&](auto s) { return v2::encode_bulk_read(s, entries); });
  const Bytes records{1, 0x00, 0x08, 0, 0};
  (void)b.call([&](auto s) { return v2::encode_sync_write(s, mx2::kGoalPosition, 4, records); });
  Bytes bad(64);
  bad.resize(v2::encode_ping(bad, 4));
  bad.back() ^= 0x11;
  (void)b.send(bad);
  const VirtualBusCounters& c = b.bus->counters();
  EXPECT_EQ(c.instructions, 5U);
  EXPECT_EQ(c.replies, 1U + 1U + 3U + 1U + 1U);
  EXPECT_EQ(c.error_replies, 2U);  // access error, CRC error
  EXPECT_EQ(c.bad_packets, 1U);
  EXPECT_EQ(c.sync_reads, 1U);
  EXPECT_EQ(c.bulk_reads, 1U);
  EXPECT_EQ(c.sync_writes, 1U);
  EXPECT_EQ(c.dropped + c.corrupted + c.silenced, 0U);
}

TEST(VirtualBusV2, InjectedFaultsActAfterTheStartCycleAndAreCounted) {
  VirtualBusV2::Options options;
  options.faults.silent[5] = true;
  options.faults.start_after_cycles = 1;
  BenchV2 b(options);
  const std::array<std::uint8_t, 3> ids{4, 5, 6};
  auto sync_read = [&] {
    return b.call([&](auto s) { return v2::encode_sync_read(s, mx2::kGoalPosition, 4, ids); });
  };
  EXPECT_EQ(sync_read().size(), 3U);  // cycle 0: no faults yet
  // From cycle 1 on, servo 5 never answers, and servo 6, waiting for it, stays silent too.
  const auto r = sync_read();
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].id, 4);
  EXPECT_TRUE(b.call([](auto s) { return v2::encode_ping(s, 5); }).empty());
  EXPECT_EQ(b.bus->counters().silenced, 2U);
  EXPECT_EQ(b.bus->counters().replies, 4U);

  VirtualBusV2::Options lossy;
  lossy.faults.drop_probability = 1.0;
  BenchV2 dropped(lossy);
  EXPECT_TRUE(dropped.call([](auto s) { return v2::encode_ping(s, kBroadcastId); }).empty());
  EXPECT_EQ(dropped.bus->counters().dropped, 20U);
  EXPECT_EQ(dropped.bus->counters().replies, 0U);

  VirtualBusV2::Options noisy;
  noisy.faults.corrupt_probability = 1.0;
  BenchV2 corrupted(noisy);
  Bytes ping(16);
  ping.resize(v2::encode_ping(ping, 3));
  const Bytes wire = corrupted.raw(ping);
  EXPECT_FALSE(wire.empty());
  EXPECT_TRUE(test::parse_all(Protocol::kV2, PacketParser::Role::kHost, wire).empty());
  EXPECT_EQ(corrupted.bus->counters().corrupted, 1U);
  EXPECT_EQ(corrupted.bus->counters().replies, 1U);
}

}  // namespace
}  // namespace stride::hal::dxl
