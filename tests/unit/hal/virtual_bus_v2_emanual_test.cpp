// The protocol 2.0 virtual bus against the ROBOTIS e-manual where an independent client found
// it departing (issue 24): FACTORY_RESET options (0xFF all, 0x01 all but the ID, 0x02 all but
// the ID and the baud rate), Goal Position outside [Min, Max Position Limit] in position
// control mode. The FACTORY_RESET exchange is written out byte by byte, CRCs computed outside
// Stride (the status packet is the one in the issue, with the expected value).
#include <gtest/gtest.h>

#include <array>

#include "bench_v2.hpp"

namespace stride::hal::dxl {
namespace {

using test::BenchV2;
using test::Bytes;

std::uint8_t write_one(BenchV2& b, std::uint8_t id, std::uint16_t address, std::uint8_t value) {
  const std::array<std::uint8_t, 1> data{value};
  const auto r = b.call([&](auto s) { return v2::encode_write(s, id, address, data); });
  return r.size() == 1 ? r[0].error : 0xEE;
}

std::uint8_t write_u32(BenchV2& b, std::uint8_t id, std::uint16_t address, std::uint32_t v) {
  const std::array<std::uint8_t, 4> data{
      static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
      static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24)};
  const auto r = b.call([&](auto s) { return v2::encode_write(s, id, address, data); });
  return r.size() == 1 ? r[0].error : 0xEE;
}

std::uint8_t factory_reset(BenchV2& b, std::uint8_t id, std::uint8_t option) {
  const auto r = b.call([&](auto s) { return v2::encode_factory_reset(s, id, option); });
  return r.size() == 1 && r[0].id == id ? r[0].error : 0xEE;
}

TEST(VirtualBusV2EManual, FactoryResetOption2KeepsIdAndBaudRate) {
  BenchV2 b;
  // WRITE Baud Rate (8) = 3 to ID 6, FACTORY_RESET option 0x02, READ Baud Rate.
  const Bytes write_baud{0xFF, 0xFF, 0xFD, 0x00, 0x06, 0x06, 0x00,
                         0x03, 0x08, 0x00, 0x03, 0x07, 0x64};
  const Bytes ok{0xFF, 0xFF, 0xFD, 0x00, 0x06, 0x04, 0x00, 0x55, 0x00, 0xCA, 0x8D};
  EXPECT_EQ(b.raw(write_baud), ok);
  ASSERT_EQ(write_one(b, 6, mx2::kReturnDelayTime, 0), 0);
  const Bytes reset{0xFF, 0xFF, 0xFD, 0x00, 0x06, 0x04, 0x00, 0x06, 0x02, 0xC0, 0x67};
  EXPECT_EQ(b.raw(reset), ok);
  const Bytes read_baud{0xFF, 0xFF, 0xFD, 0x00, 0x06, 0x07, 0x00,
                        0x02, 0x08, 0x00, 0x01, 0x00, 0x30, 0x0B};
  const Bytes baud_3{0xFF, 0xFF, 0xFD, 0x00, 0x06, 0x05, 0x00, 0x55, 0x00, 0x03, 0x5F, 0x49};
  EXPECT_EQ(b.raw(read_baud), baud_3);
  // Everything else is back to its factory value.
  EXPECT_EQ(b.bus->peek(6, mx2::kReturnDelayTime, 1), 250U);
  EXPECT_EQ(b.bus->peek(6, mx2::kId, 1), 6U);
}

TEST(VirtualBusV2EManual, FactoryResetOption1KeepsOnlyTheId) {
  BenchV2 b;
  ASSERT_EQ(write_one(b, 6, mx2::kBaudRate, 3), 0);
  ASSERT_EQ(write_one(b, 6, mx2::kReturnDelayTime, 0), 0);
  EXPECT_EQ(factory_reset(b, 6, 0x01), 0);
  EXPECT_EQ(b.bus->peek(6, mx2::kBaudRate, 1), 1U);
  EXPECT_EQ(b.bus->peek(6, mx2::kReturnDelayTime, 1), 250U);
}

TEST(VirtualBusV2EManual, FactoryResetAllResetsTheIdToo) {
  BenchV2 b;
  ASSERT_EQ(write_one(b, 1, mx2::kId, 30), 0);  // move servo 1 away so ID 1 is free
  ASSERT_EQ(write_one(b, 6, mx2::kBaudRate, 3), 0);
  // Broadcast with option 0xFF is not executed (e-manual); nobody answers a broadcast.
  EXPECT_TRUE(
      b.call([](auto s) { return v2::encode_factory_reset(s, kBroadcastId, 0xFF); }).empty());
  EXPECT_EQ(b.bus->peek(6, mx2::kBaudRate, 1), 3U);
  // To ID 6: the status packet still comes from ID 6, then the servo is ID 1 at baud 1.
  EXPECT_EQ(factory_reset(b, 6, 0xFF), 0);
  EXPECT_TRUE(b.call([](auto s) { return v2::encode_ping(s, 6); }).empty());
  const auto r = b.call([](auto s) { return v2::encode_read(s, 1, mx2::kBaudRate, 1); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].params[0], 1);
  EXPECT_EQ(b.bus->peek(30, mx2::kId, 1), 30U);  // the other servo kept its new ID
}

TEST(VirtualBusV2EManual, FactoryResetRefusesUnknownOptionsAndLengths) {
  BenchV2 b;
  ASSERT_EQ(write_one(b, 6, mx2::kBaudRate, 3), 0);
  EXPECT_EQ(factory_reset(b, 6, 0x00), v2_error::kDataRange);
  EXPECT_EQ(factory_reset(b, 6, 0x03), v2_error::kDataRange);
  const auto r =
      b.call([](auto s) { return v2::encode_instruction(s, 6, instruction::kReset, {}); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].error, v2_error::kDataLength);
  EXPECT_EQ(b.bus->peek(6, mx2::kBaudRate, 1), 3U);  // nothing was reset
}

TEST(VirtualBusV2EManual, GoalPositionOutsideThePositionLimitsIsRefused) {
  BenchV2 b;
  ASSERT_EQ(write_u32(b, 4, mx2::kGoalPosition, 2500), 0);
  ASSERT_EQ(write_u32(b, 4, mx2::kMaxPositionLimit, 3000), 0);
  ASSERT_EQ(write_u32(b, 4, mx2::kMinPositionLimit, 1000), 0);
  EXPECT_EQ(write_u32(b, 4, mx2::kGoalPosition, 3500), v2_error::kDataLimit);
  EXPECT_EQ(b.bus->peek(4, mx2::kGoalPosition, 4), 2500U);
  EXPECT_EQ(write_u32(b, 4, mx2::kGoalPosition, 999), v2_error::kDataLimit);
  EXPECT_EQ(b.bus->peek(4, mx2::kGoalPosition, 4), 2500U);
  EXPECT_EQ(write_u32(b, 4, mx2::kGoalPosition, 3000), 0);  // the limits themselves are allowed
  EXPECT_EQ(write_u32(b, 4, mx2::kGoalPosition, 1000), 0);
  // SYNC_WRITE (no status packet) and REG_WRITE + ACTION are held to the same limits.
  const Bytes records{4, 0xAC, 0x0D, 0, 0};  // 3500
  (void)b.call([&](auto s) { return v2::encode_sync_write(s, mx2::kGoalPosition, 4, records); });
  EXPECT_EQ(b.bus->peek(4, mx2::kGoalPosition, 4), 1000U);
  const std::array<std::uint8_t, 4> far{0xAC, 0x0D, 0, 0};
  auto r = b.call([&](auto s) { return v2::encode_reg_write(s, 4, mx2::kGoalPosition, far); });
  ASSERT_EQ(r.size(), 1U);
  r = b.call([](auto s) { return v2::encode_action(s, 4); });
  ASSERT_EQ(r.size(), 1U);
  EXPECT_EQ(r[0].error, v2_error::kDataLimit);
  EXPECT_EQ(b.bus->peek(4, mx2::kGoalPosition, 4), 1000U);
  // Outside position control mode (4: extended position) the limits do not apply.
  ASSERT_EQ(write_one(b, 4, mx2::kOperatingMode, 4), 0);
  EXPECT_EQ(write_u32(b, 4, mx2::kGoalPosition, 3500), 0);
  EXPECT_EQ(b.bus->peek(4, mx2::kGoalPosition, 4), 3500U);
}

}  // namespace
}  // namespace stride::hal::dxl
