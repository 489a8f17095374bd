// The emulated CM730 + MX bus: replies, status return level, error bits, alarm shutdown,
// BULK_READ chaining, lockstep motion and fault injection.
#include <gtest/gtest.h>

#include <array>

#include "dxl_test_util.hpp"
#include "stride/firmware/dynamixel_config.hpp"
#include "stride/hal/dynamixel/codec_v1.hpp"
#include "stride/hal/dynamixel/control_table.hpp"
#include "stride/hal/dynamixel/virtual_bus.hpp"

namespace stride::hal::dxl {
namespace {

using test::Bytes;

struct Bench {
  explicit Bench(VirtualBusFaults faults = {}, bool lockstep = true) {
    VirtualBus::Options options;
    options.calibration = fw::servo_calibrations(fw::ServoTable::defaults());
    options.lockstep = lockstep;
    options.faults = faults;
    FirstOrderPhysics::Options physics;
    for (std::size_t i = 0; i < kServoCount; ++i) physics.models[i] = options.calibration[i].model;
    bus = std::make_unique<VirtualBus>(options, std::make_unique<FirstOrderPhysics>(physics));
  }
  // Sends a packet and returns the status packets it produced.
  std::vector<Packet> send(const Bytes& packet) {
    std::vector<std::uint8_t> out;
    delay_us = 0;
    bus->receive(packet, out, delay_us);
    return test::parse_all(Protocol::kV1, PacketParser::Role::kHost, out);
  }
  template <typename F>
  std::vector<Packet> call(F encode) {
    Bytes b(300);
    b.resize(encode(std::span<std::uint8_t>(b)));
    return send(b);
  }
  std::unique_ptr<VirtualBus> bus;
  std::int64_t delay_us = 0;
};

TEST(VirtualBus, PingReadAndReturnDelay) {
  Bench bench;
  auto r = bench.call([](auto b) { return v1::encode_ping(b, 3); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].id, 3);
  EXPECT_EQ(r[0].error, 0);
  EXPECT_EQ(bench.delay_us, 500);  // factory return delay 250 * 2 us
  r = bench.call([](auto b) { return v1::encode_read(b, 7, mx1::kModelNumber, 2); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(read_u16(r[0].params.data()), mx1::kModelMx106);
  r = bench.call([](auto b) { return v1::encode_read(b, 1, mx1::kModelNumber, 2); });
  EXPECT_EQ(read_u16(r[0].params.data()), mx1::kModelMx64);
  r = bench.call([](auto b) { return v1::encode_read(b, kCm730Id, cm730::kAccelZ, 2); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(read_u16(r[0].params.data()), 640);  // upright: +1 g
  EXPECT_TRUE(bench.call([](auto b) { return v1::encode_ping(b, 77); }).empty());
}

TEST(VirtualBus, StatusReturnLevelAndBroadcast) {
  Bench bench;
  const std::uint8_t one = 1;
  EXPECT_TRUE(bench
                  .call([&](auto b) {
                    return v1::encode_write(b, kBroadcastId, mx1::kStatusReturnLevel,
                                            std::span(&one, 1));
                  })
                  .empty());
  const std::uint8_t zero = 0;
  EXPECT_TRUE(bench
                  .call([&](auto b) {
                    return v1::encode_write(b, kBroadcastId, mx1::kReturnDelayTime,
                                            std::span(&zero, 1));
                  })
                  .empty());
  // Level 1: WRITE is silent, READ and PING answer; the return delay is now 0.
  const std::uint8_t led = 1;
  EXPECT_TRUE(
      bench.call([&](auto b) { return v1::encode_write(b, 5, mx1::kLed, std::span(&led, 1)); })
          .empty());
  auto r = bench.call([](auto b) { return v1::encode_read(b, 5, mx1::kLed, 1); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].params[0], 1);
  EXPECT_EQ(bench.delay_us, 0);
  // Level 0: only PING answers.
  EXPECT_TRUE(bench
                  .call([&](auto b) {
                    return v1::encode_write(b, 5, mx1::kStatusReturnLevel, std::span(&zero, 1));
                  })
                  .empty());
  EXPECT_TRUE(bench.call([](auto b) { return v1::encode_read(b, 5, mx1::kLed, 1); }).empty());
  EXPECT_EQ(bench.call([](auto b) { return v1::encode_ping(b, 5); }).size(), 1U);
}

TEST(VirtualBus, ErrorBits) {
  Bench bench;
  // Range: P gain 255 > 254 is refused and not applied.
  const std::uint8_t p = 255;
  auto r =
      bench.call([&](auto b) { return v1::encode_write(b, 2, mx1::kPGain, std::span(&p, 1)); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].error, error_bits::kRange);
  EXPECT_EQ(bench.bus->peek(2, mx1::kPGain), 32);
  // Angle limit: CW limit 1000, goal 500.
  const std::array<std::uint8_t, 2> cw{0xE8, 0x03};
  (void)bench.call([&](auto b) { return v1::encode_write(b, 2, mx1::kCwAngleLimit, cw); });
  const std::array<std::uint8_t, 2> goal{0xF4, 0x01};
  r = bench.call([&](auto b) { return v1::encode_write(b, 2, mx1::kGoalPosition, goal); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].error, error_bits::kAngleLimit);
  // Instruction: unknown code, ACTION without REG_WRITE.
  r = bench.call([](auto b) { return v1::encode_instruction(b, 2, 0x44, {}); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].error, error_bits::kInstruction);
  r = bench.call([](auto b) { return v1::encode_action(b, 2); });
  EXPECT_EQ(r[0].error, error_bits::kInstruction);
  // REG_WRITE then ACTION applies the write.
  const std::uint8_t led = 1;
  (void)bench.call(
      [&](auto b) { return v1::encode_reg_write(b, 2, mx1::kLed, std::span(&led, 1)); });
  EXPECT_EQ(bench.bus->peek(2, mx1::kLed), 0);
  EXPECT_EQ(bench.bus->peek(2, mx1::kRegistered), 1);
  r = bench.call([](auto b) { return v1::encode_action(b, 2); });
  EXPECT_EQ(r[0].error, 0);
  EXPECT_EQ(bench.bus->peek(2, mx1::kLed), 1);
  // Checksum: a damaged packet addressed to servo 2.
  Bytes bad(300);
  bad.resize(v1::encode_ping(bad, 2));
  bad.back() ^= 0x5A;
  r = bench.send(bad);
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].error, error_bits::kChecksum);
  EXPECT_EQ(bench.bus->counters().bad_packets, 1U);
  // Range, angle limit, two instruction errors, checksum: 5 of the 8 replies carry an error.
  EXPECT_EQ(bench.bus->counters().replies, 8U);
  EXPECT_EQ(bench.bus->counters().error_replies, 5U);
}

TEST(VirtualBus, OverheatingTriggersAlarmShutdown) {
  VirtualBusFaults faults;
  faults.overheat[13] = true;
  Bench bench(faults);
  const std::uint8_t on = 1;
  auto r = bench.call(
      [&](auto b) { return v1::encode_write(b, 13, mx1::kTorqueEnable, std::span(&on, 1)); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_NE(r[0].error & error_bits::kOverheating, 0);
  EXPECT_EQ(bench.bus->peek(13, mx1::kTorqueEnable), 0);  // shutdown: torque stays off
  r = bench.call(
      [&](auto b) { return v1::encode_write(b, 12, mx1::kTorqueEnable, std::span(&on, 1)); });
  EXPECT_EQ(r[0].error, 0);
  EXPECT_EQ(bench.bus->peek(12, mx1::kTorqueEnable), 1);
}

TEST(VirtualBus, BulkReadRepliesInOrderAndStopsAtASilentDevice) {
  VirtualBusFaults faults;
  faults.silent[3] = true;
  Bench bench(faults);
  const std::array<BulkReadEntry, 4> entries{BulkReadEntry{kCm730Id, 30, 21},
                                             BulkReadEntry{1, 36, 8}, BulkReadEntry{3, 36, 8},
                                             BulkReadEntry{4, 36, 8}};
  auto r = bench.call([&](auto b) { return v1::encode_bulk_read(b, entries); });
  ASSERT_EQ(r.size(), 2U);  // CM730 and servo 1; 3 is silent, so 4 never gets its turn
  EXPECT_EQ(r[0].id, kCm730Id);
  EXPECT_EQ(r[0].param_count, 21);
  EXPECT_EQ(r[1].id, 1);
  EXPECT_EQ(r[1].param_count, 8);
  EXPECT_EQ(bench.bus->counters().silenced, 1U);
}

TEST(VirtualBus, LockstepMotionFollowsTheGoalAtTheMovingSpeed) {
  Bench bench;
  // Servo 9 (r_hip_roll, direction +1, offset 0): torque on, goal 2048 + 400, speed 50 units.
  const std::array<std::uint8_t, 12> records{9, 0, 0, 32, 0, 0x90, 0x09, 50, 0, 0xFF, 0x03, 0};
  (void)bench.call([&](auto b) {
    return v1::encode_sync_write(b, mx1::kDGain, 10, std::span(records.data(), 11));
  });
  const std::uint8_t on = 1;
  (void)bench.call(
      [&](auto b) { return v1::encode_write(b, 9, mx1::kTorqueEnable, std::span(&on, 1)); });
  const std::array<BulkReadEntry, 1> entry{BulkReadEntry{9, 36, 8}};
  std::uint16_t position = 0;
  for (int tick = 0; tick < 100; ++tick) {  // 1 s at 100 Hz
    auto r = bench.call([&](auto b) { return v1::encode_bulk_read(b, entry); });
    ASSERT_EQ(r.size(), 1U);
    position = read_u16(r[0].params.data());
  }
  // 50 units * 0.114 rpm = 0.597 rad/s -> ~389 ticks in 1 s (first-order near the end).
  EXPECT_GT(position, 2048 + 300);
  EXPECT_LE(position, 2048 + 400);
}

TEST(VirtualBus, FaultSpecsParseAndRejectBadInput) {
  VirtualBusFaults f;
  EXPECT_TRUE(f.add("drop:0.05").is_ok());
  EXPECT_DOUBLE_EQ(f.drop_probability, 0.05);
  EXPECT_TRUE(f.add("silent:7").is_ok());
  EXPECT_TRUE(f.silent[7]);
  EXPECT_TRUE(f.add("overheat:13").is_ok());
  EXPECT_TRUE(f.add("start:100").is_ok());
  EXPECT_EQ(f.start_after_cycles, 100U);
  EXPECT_FALSE(f.add("drop:2").is_ok());
  EXPECT_FALSE(f.add("silent:x").is_ok());
  EXPECT_FALSE(f.add("melt:3").is_ok());
  EXPECT_NE(f.add("nocolon").message().find("nocolon"), std::string::npos);
}

}  // namespace
}  // namespace stride::hal::dxl
