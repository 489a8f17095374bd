// Protocol 1.0 packets compared byte for byte with the ROBOTIS e-manual "Protocol 1.0" examples.
#include <gtest/gtest.h>

#include <array>

#include "dxl_test_util.hpp"
#include "stride/hal/dynamixel/codec_v1.hpp"

namespace stride::hal::dxl {
namespace {

using test::Bytes;

Bytes buf() {
  return Bytes(300);
}

TEST(CodecV1, ChecksumExampleFromManual) {
  // ID 1, LEN 5, WRITE, params 0C 64 AA -> checksum DC.
  Bytes out = buf();
  const std::array<std::uint8_t, 2> data{0x64, 0xAA};
  out.resize(v1::encode_write(out, 0x01, 0x0C, data));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0x01, 0x05, 0x03, 0x0C, 0x64, 0xAA, 0xDC}));
}

TEST(CodecV1, PingAndStatus) {
  Bytes out = buf();
  out.resize(v1::encode_ping(out, 1));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0x01, 0x02, 0x01, 0xFB}));
  out = buf();
  out.resize(v1::encode_status(out, 1, 0, {}));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0x01, 0x02, 0x00, 0xFC}));
  out = buf();
  out.resize(v1::encode_status(out, 1, 0x24, {}));  // overload + overheating example
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0x01, 0x02, 0x24, 0xD8}));
}

TEST(CodecV1, ReadAndStatus) {
  Bytes out = buf();
  out.resize(v1::encode_read(out, 1, 0x2B, 1));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0x01, 0x04, 0x02, 0x2B, 0x01, 0xCC}));
  out = buf();
  const std::array<std::uint8_t, 1> temperature{0x20};
  out.resize(v1::encode_status(out, 1, 0, temperature));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0x01, 0x03, 0x00, 0x20, 0xDB}));
}

TEST(CodecV1, WriteRegWriteActionReset) {
  Bytes out = buf();
  const std::array<std::uint8_t, 1> id{0x01};
  out.resize(v1::encode_write(out, 0xFE, 0x03, id));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0xFE, 0x04, 0x03, 0x03, 0x01, 0xF6}));
  out = buf();
  const std::array<std::uint8_t, 2> goal{0xF4, 0x01};
  out.resize(v1::encode_reg_write(out, 0x01, 0x1E, goal));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0x01, 0x05, 0x04, 0x1E, 0xF4, 0x01, 0xE2}));
  out = buf();
  out.resize(v1::encode_action(out, 0xFE));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0xFE, 0x02, 0x05, 0xFA}));
  out = buf();
  out.resize(v1::encode_reset(out, 0x00));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0x00, 0x02, 0x06, 0xF7}));
}

TEST(CodecV1, SyncWrite) {
  const Bytes records{0x00, 0x10, 0x00, 0x50, 0x01, 0x01, 0x20, 0x02, 0x60, 0x03};
  Bytes out = buf();
  out.resize(v1::encode_sync_write(out, 0x1E, 0x04, records));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0xFE, 0x0E, 0x83, 0x1E, 0x04, 0x00, 0x10, 0x00, 0x50, 0x01,
                        0x01, 0x20, 0x02, 0x60, 0x03, 0x67}));
  // A record block that is not a multiple of length + 1 is refused.
  Bytes bad = buf();
  EXPECT_EQ(v1::encode_sync_write(bad, 0x1E, 0x04, std::span(records).first(9)), 0U);
}

TEST(CodecV1, BulkReadAndReplies) {
  const std::array<BulkReadEntry, 2> entries{BulkReadEntry{1, 0x1E, 2}, BulkReadEntry{2, 0x24, 2}};
  Bytes out = buf();
  out.resize(v1::encode_bulk_read(out, entries));
  EXPECT_EQ(out,
            (Bytes{0xFF, 0xFF, 0xFE, 0x09, 0x92, 0x00, 0x02, 0x01, 0x1E, 0x02, 0x02, 0x24, 0x1D}));
  const std::array<std::uint8_t, 2> value{0x00, 0x80};
  out = buf();
  out.resize(v1::encode_status(out, 1, 0, value));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0x01, 0x04, 0x00, 0x00, 0x80, 0x7A}));
  out = buf();
  out.resize(v1::encode_status(out, 2, 0, value));
  EXPECT_EQ(out, (Bytes{0xFF, 0xFF, 0x02, 0x04, 0x00, 0x00, 0x80, 0x79}));
}

TEST(CodecV1, RefusesSmallBuffersAndLongPackets) {
  std::array<std::uint8_t, 5> small{};
  EXPECT_EQ(v1::encode_ping(small, 1), 0U);
  Bytes big(300);
  const Bytes data(254, 0x11);
  EXPECT_EQ(v1::encode_write(big, 1, 0, data), 0U);  // 255 parameters do not fit LEN
  const Bytes max_data(252, 0x11);
  EXPECT_EQ(v1::encode_write(big, 1, 0, max_data), 259U);
}

}  // namespace
}  // namespace stride::hal::dxl
