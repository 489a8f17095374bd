// Dynamixel bus budget and codec cost.
//
// Part 1 (printed table): bytes on the wire and bus time of one control tick of the igus robot
// (protocol 1.0: the per-tick SYNC_WRITE of 20 servos as DynamixelRobot builds it, and the
// BULK_READ of the CM730 + 20 servos with its 21 status packets), at 1 and 3 Mbaud, with the
// servos' return delay (0 as DynamixelRobot sets it; the factory 250 = 500 us shown for
// comparison). Byte counts come from the real encoders, and are checked against a real
// DynamixelRobot cycle on the in-process virtual bus. Time = bytes * 10 bits / baud + N_replies
// * return delay. Also the highest loop rate the bus allows (100 % and 60 % bus utilisation).
// Part 2 (Google Benchmark): encoder and parser cost per packet, and a whole DynamixelRobot
// read+write cycle against the in-process virtual bus (which includes the emulation's cost).
#include <benchmark/benchmark.h>

#include <array>
#include <cstdio>
#include <memory>
#include <vector>

#include "stride/hal/dynamixel/codec_v1.hpp"
#include "stride/hal/dynamixel/codec_v2.hpp"
#include "stride/hal/dynamixel/dynamixel_robot.hpp"
#include "stride/hal/dynamixel/packet_parser.hpp"
#include "stride/hal/dynamixel/virtual_bus.hpp"
#include "stride/hal/dynamixel/virtual_bus_stream.hpp"

namespace dxl = stride::hal::dxl;
using stride::hal::kServoCount;

namespace {

struct TickBytes {
  std::size_t sync_write = 0;  // host -> bus
  std::size_t bulk_read = 0;   // host -> bus
  std::size_t replies = 0;     // bus -> host
  std::size_t reply_count = 0;
};

TickBytes tick_bytes() {
  TickBytes t;
  std::array<std::uint8_t, dxl::kMaxPacketBytes> buf{};
  std::vector<std::uint8_t> records;
  for (std::uint8_t id = 1; id <= kServoCount; ++id) {  // 20 servos, 8 bytes from P gain (28)
    records.push_back(id);
    records.insert(records.end(), {32, 0, 0x00, 0x08, 100, 0, 0xFF, 0x03});
  }
  t.sync_write = dxl::v1::encode_sync_write(buf, 28, 8, records);
  std::vector<dxl::BulkReadEntry> entries{{stride::hal::kCm730Id, 30, 21}};
  for (std::uint8_t id = 1; id <= kServoCount; ++id) entries.push_back({id, 36, 8});
  t.bulk_read = dxl::v1::encode_bulk_read(buf, entries);
  for (const auto& e : entries) {
    std::vector<std::uint8_t> data(e.length, 0);
    t.replies += dxl::v1::encode_status(buf, e.id, 0, data);
  }
  t.reply_count = entries.size();
  return t;
}

// Bytes DynamixelRobot really sends and receives per steady-state tick when every servo's goal
// changes (in-process virtual bus).
std::pair<std::uint64_t, std::uint64_t> measured_cycle_bytes() {
  dxl::VirtualBus::Options options;
  options.lockstep = true;
  for (std::size_t i = 0; i < kServoCount; ++i) {
    options.calibration[i].model =
        i < 6 || i >= 18 ? dxl::ServoModelId::kMx64 : dxl::ServoModelId::kMx106;
  }
  dxl::FirstOrderPhysics::Options physics;
  for (std::size_t i = 0; i < kServoCount; ++i) physics.models[i] = options.calibration[i].model;
  dxl::VirtualBus bus(options, std::make_unique<dxl::FirstOrderPhysics>(physics));
  dxl::DynamixelRobot::Options ro;
  ro.calibration = options.calibration;
  std::unique_ptr<dxl::DynamixelRobot> robot;
  if (!dxl::DynamixelRobot::create(std::make_unique<dxl::VirtualBusStream>(bus, 1'000'000), ro,
                                   robot)) {
    return {0, 0};
  }
  stride::hal::SensorFrame frame;
  stride::hal::CommandFrame command;
  for (auto& s : command.servos) s.torque_enable = true;
  for (int t = 0; t < 3; ++t) {  // settle: first write sends gains and torque enable too
    command.tick = t;
    for (auto& s : command.servos) s.position_rad = 0.001 * t;
    robot->read(frame);
    robot->write(command);
  }
  const auto tx0 = robot->diagnostics().bytes_tx;
  const auto rx0 = robot->diagnostics().bytes_rx;
  command.tick = 3;
  for (auto& s : command.servos) s.position_rad = 0.01;
  robot->read(frame);
  robot->write(command);
  return {robot->diagnostics().bytes_tx - tx0, robot->diagnostics().bytes_rx - rx0};
}

void print_budget() {
  const TickBytes t = tick_bytes();
  const std::size_t tx = t.sync_write + t.bulk_read;
  const std::size_t total = tx + t.replies;
  const auto [measured_tx, measured_rx] = measured_cycle_bytes();
  std::printf("Dynamixel 1.0 tick (20-servo SYNC_WRITE + BULK_READ of CM730 + 20 servos):\n");
  std::printf("  SYNC_WRITE %zu B, BULK_READ %zu B, %zu status packets %zu B: %zu B per tick\n",
              t.sync_write, t.bulk_read, t.reply_count, t.replies, total);
  std::printf("  DynamixelRobot measured on the virtual bus: %llu B sent, %llu B received%s\n",
              static_cast<unsigned long long>(measured_tx),
              static_cast<unsigned long long>(measured_rx),
              measured_tx == tx && measured_rx == t.replies ? " (matches)" : " (MISMATCH)");
  for (const std::uint32_t baud : {1'000'000U, 3'000'000U}) {
    for (const int return_delay_us : {0, 500}) {
      const double wire_ms = static_cast<double>(dxl::wire_time_ns(total, baud)) * 1e-6;
      const double bus_ms = wire_ms + t.reply_count * return_delay_us * 1e-3;
      std::printf(
          "  %.0f Mbaud, return delay %3d us: bus time %.3f ms = %.1f %% of a 10 ms period; "
          "max loop rate %.0f Hz (100 %% bus), %.0f Hz (60 %% bus)\n",
          baud / 1e6, return_delay_us, bus_ms, bus_ms / 10.0 * 100.0, 1000.0 / bus_ms,
          600.0 / bus_ms);
    }
  }
  std::fflush(stdout);
}

std::vector<std::uint8_t> sync_records() {
  std::vector<std::uint8_t> records;
  for (std::uint8_t id = 1; id <= kServoCount; ++id) {
    records.push_back(id);
    records.insert(records.end(), {32, 0, 0x00, 0x08, 100, 0, 0xFF, 0x03});
  }
  return records;
}

void BM_EncodeSyncWriteV1(benchmark::State& state) {
  const auto records = sync_records();
  std::array<std::uint8_t, 512> buf{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(dxl::v1::encode_sync_write(buf, 28, 8, records));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EncodeSyncWriteV1);

void BM_EncodeBulkReadV1(benchmark::State& state) {
  std::vector<dxl::BulkReadEntry> entries{{200, 30, 21}};
  for (std::uint8_t id = 1; id <= kServoCount; ++id) entries.push_back({id, 36, 8});
  std::array<std::uint8_t, 512> buf{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(dxl::v1::encode_bulk_read(buf, entries));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EncodeBulkReadV1);

// Parsing the 21 status packets of one BULK_READ (items = packets).
void BM_ParseBulkReadRepliesV1(benchmark::State& state) {
  std::vector<std::uint8_t> stream;
  std::array<std::uint8_t, 64> buf{};
  const std::vector<std::uint8_t> cm(21, 0x11);
  stream.insert(stream.end(), buf.begin(), buf.begin() + dxl::v1::encode_status(buf, 200, 0, cm));
  for (std::uint8_t id = 1; id <= kServoCount; ++id) {
    const std::vector<std::uint8_t> data{0x00, 0x08, 0x10, 0x00, 0x20, 0x04, 150, 35};
    stream.insert(stream.end(), buf.begin(),
                  buf.begin() + dxl::v1::encode_status(buf, id, 0, data));
  }
  dxl::PacketParser parser(dxl::Protocol::kV1, dxl::PacketParser::Role::kHost);
  dxl::Packet packet;
  for (auto _ : state) {
    parser.reset();
    (void)parser.feed(stream);
    int n = 0;
    while (parser.next(packet)) ++n;
    benchmark::DoNotOptimize(n);
  }
  state.SetItemsProcessed(state.iterations() * 21);
}
BENCHMARK(BM_ParseBulkReadRepliesV1);

void BM_EncodeParseV2Status(benchmark::State& state) {
  std::array<std::uint8_t, 64> buf{};
  const std::vector<std::uint8_t> data{0xFF, 0xFF, 0xFD, 0x00, 0x20, 0x04, 150, 35};
  dxl::PacketParser parser(dxl::Protocol::kV2, dxl::PacketParser::Role::kHost);
  dxl::Packet packet;
  for (auto _ : state) {
    const std::size_t n = dxl::v2::encode_status(buf, 7, 0, data);
    (void)parser.feed(std::span(buf.data(), n));
    benchmark::DoNotOptimize(parser.next(packet));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EncodeParseV2Status);

void BM_DynamixelRobotCycleOnVirtualBus(benchmark::State& state) {
  dxl::VirtualBus::Options options;
  options.lockstep = true;
  dxl::FirstOrderPhysics::Options physics;
  for (std::size_t i = 0; i < kServoCount; ++i) physics.models[i] = options.calibration[i].model;
  dxl::VirtualBus bus(options, std::make_unique<dxl::FirstOrderPhysics>(physics));
  dxl::DynamixelRobot::Options ro;
  ro.calibration = options.calibration;
  std::unique_ptr<dxl::DynamixelRobot> robot;
  if (!dxl::DynamixelRobot::create(std::make_unique<dxl::VirtualBusStream>(bus, 1'000'000), ro,
                                   robot)) {
    state.SkipWithError("start-up failed");
    return;
  }
  stride::hal::SensorFrame frame;
  stride::hal::CommandFrame command;
  for (auto& s : command.servos) s.torque_enable = true;
  stride::hal::Tick tick = 0;
  for (auto _ : state) {
    command.tick = ++tick;
    for (auto& s : command.servos) s.position_rad = 0.001 * static_cast<double>(tick % 100);
    robot->read(frame);
    robot->write(command);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DynamixelRobotCycleOnVirtualBus);

}  // namespace

int main(int argc, char** argv) {
  print_budget();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
