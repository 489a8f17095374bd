// SerialPort on a real pseudo-terminal (served by PtyBusServer): exclusive open, read
// timeouts without busy waiting, bad rates and devices named in errors, a ping round trip.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <atomic>
#include <thread>

#include "stride/hal/dynamixel/codec_v1.hpp"
#include "stride/hal/dynamixel/packet_parser.hpp"
#include "stride/hal/dynamixel/pty_bus_server.hpp"
#include "stride/hal/dynamixel/serial_port.hpp"
#include "stride/hal/dynamixel/virtual_bus.hpp"
#include "temp_dir.hpp"

namespace stride::hal::dxl {
namespace {

std::int64_t cpu_ns() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return (u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1'000'000'000LL +
         (u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1000LL;
}

TEST(SerialPort, RejectsBadRateAndMissingDevice) {
  std::unique_ptr<SerialPort> port;
  Status s = SerialPort::open("/dev/null", 1234567, port);
  ASSERT_FALSE(s.is_ok());
  EXPECT_NE(s.message().find("1234567"), std::string::npos);
  s = SerialPort::open("/nonexistent/ttyUSB9", 1'000'000, port);
  ASSERT_FALSE(s.is_ok());
  EXPECT_NE(s.message().find("/nonexistent/ttyUSB9"), std::string::npos);
  EXPECT_TRUE(SerialPort::is_standard_baud(1'000'000));
  EXPECT_TRUE(SerialPort::is_standard_baud(3'000'000));
  EXPECT_TRUE(SerialPort::is_standard_baud(57'600));
}

TEST(SerialPort, PseudoTerminalIsExclusiveAndTimesOutWithoutSpinning) {
  test::TempDir dir;
  std::unique_ptr<PtyBusServer> server;
  ASSERT_TRUE(PtyBusServer::create((dir.path() / "bus").string(), server).is_ok());
  std::unique_ptr<SerialPort> port;
  const Status s = SerialPort::open((dir.path() / "bus").string(), 3'000'000, port);
  ASSERT_TRUE(s.is_ok()) << s.message();
  EXPECT_TRUE(port->is_pseudo_terminal());
  EXPECT_FALSE(port->latency_timer_set());  // a pty has none: skipped quietly
  EXPECT_EQ(port->baud(), 3'000'000U);
  std::unique_ptr<SerialPort> second;
  const Status busy = SerialPort::open((dir.path() / "bus").string(), 1'000'000, second);
  ASSERT_FALSE(busy.is_ok());
  EXPECT_NE(busy.message().find("in use"), std::string::npos);
  // Nothing is served: a 50 ms read times out after about 50 ms, using little CPU.
  std::array<std::uint8_t, 16> buf{};
  const std::int64_t cpu0 = cpu_ns();
  const std::int64_t t0 = monotonic_ns();
  EXPECT_EQ(port->read_some(buf, t0 + 50'000'000), 0);
  const std::int64_t elapsed = monotonic_ns() - t0;
  EXPECT_GE(elapsed, 50'000'000);
  EXPECT_LT(cpu_ns() - cpu0, 10'000'000);  // a spinning wait would burn ~50 ms of CPU
}

TEST(SerialPort, PingRoundTripThroughThePtyServer) {
  test::TempDir dir;
  std::unique_ptr<PtyBusServer> server;
  ASSERT_TRUE(PtyBusServer::create((dir.path() / "bus").string(), server).is_ok());
  VirtualBus::Options options;
  FirstOrderPhysics::Options physics;
  VirtualBus bus(options, std::make_unique<FirstOrderPhysics>(physics));
  std::atomic<bool> stop{false};
  std::thread serving([&] { (void)server->serve(bus, stop); });
  std::unique_ptr<SerialPort> port;
  ASSERT_TRUE(SerialPort::open((dir.path() / "bus").string(), 1'000'000, port).is_ok());
  std::array<std::uint8_t, 16> tx{};
  const std::size_t n = v1::encode_ping(tx, 200);
  ASSERT_TRUE(port->write(std::span(tx.data(), n), monotonic_ns() + 100'000'000));
  PacketParser parser(Protocol::kV1, PacketParser::Role::kHost);
  Packet reply;
  bool got = false;
  const std::int64_t deadline = monotonic_ns() + 1'000'000'000;
  std::array<std::uint8_t, 64> rx{};
  while (!got) {
    const auto r = port->read_some(rx, deadline);
    if (r <= 0) break;
    (void)parser.feed(std::span(rx.data(), static_cast<std::size_t>(r)));
    got = parser.next(reply);
  }
  stop.store(true);
  serving.join();
  ASSERT_TRUE(got);
  EXPECT_EQ(reply.id, 200);
  EXPECT_EQ(reply.error, 0);
}

}  // namespace
}  // namespace stride::hal::dxl
