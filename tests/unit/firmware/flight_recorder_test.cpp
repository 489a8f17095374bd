// The flight recorder in process: the ring buffer, the tick encoding, a recorded loop read back
// exactly, no allocation in the loop, whole ticks dropped and counted when the ring is full,
// and logs cut short or damaged read up to their last complete block.
#include "stride/firmware/recorder/flight_recorder.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "counting_allocator.hpp"
#include "stride/firmware/control_loop.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/hal/scripted_robot.hpp"
#include "temp_dir.hpp"

namespace stride::fw {
namespace {

namespace fl = flight_log;

float as_logged(double value) {
  return static_cast<float>(value);
}

TEST(RecordRing, KeepsRecordsInOrderAcrossTheWrap) {
  fl::RecordRing ring(64);
  std::vector<std::uint8_t> out;
  for (std::uint8_t round = 0; round < 50; ++round) {
    const std::vector<std::uint8_t> a(13, round), b(7, static_cast<std::uint8_t>(round + 100));
    ASSERT_TRUE(ring.try_push(a.data(), 13));
    ASSERT_TRUE(ring.try_push(b.data(), 7));
    ASSERT_TRUE(ring.try_pop(out));
    EXPECT_EQ(out, a);
    ASSERT_TRUE(ring.try_pop(out));
    EXPECT_EQ(out, b);
    EXPECT_FALSE(ring.try_pop(out));
  }
}

TEST(RecordRing, RefusesWholeRecordsThatDoNotFit) {
  fl::RecordRing ring(64);
  const std::vector<std::uint8_t> big(40, 1), small(16, 2);
  ASSERT_TRUE(ring.try_push(big.data(), 40));     // 44 bytes used
  EXPECT_FALSE(ring.try_push(small.data(), 17));  // needs 21, 20 free
  EXPECT_TRUE(ring.try_push(small.data(), 16));   // needs 20
  EXPECT_EQ(ring.used(), 64u);
  std::vector<std::uint8_t> out;
  ASSERT_TRUE(ring.try_pop(out));
  EXPECT_EQ(out, big);
  ASSERT_TRUE(ring.try_pop(out));
  EXPECT_EQ(out, small);
}

TEST(FlightLogFormat, TickRoundTripsAsFloat32) {
  hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();
  sensors.tick = 41;
  sensors.servos[3].load = -0.3;
  sensors.servos[3].error_flags = hal::error_bits::kOverheating;
  sensors.servos[3].health = hal::DeviceHealth::kError;
  sensors.cm730.gyro_rad_s = {0.1, -0.2, 0.3};
  sensors.cm730.buttons = 2;
  hal::CommandFrame commands;
  commands.tick = 42;
  commands.servos[7] = {0.123456789, 1.5, 40, 1, 2, 0.75, true};
  const fl::ParamChange changes[] = {{3, 0.85}, {250, -1e-9}};
  const fl::TickMeta meta{42, 5, MotionState::kWalk, true, 0.25F};
  std::vector<std::uint8_t> payload(fl::kTickFixedBytes + 2 * fl::kParamChangeBytes);
  ASSERT_EQ(fl::encode_tick(meta, sensors, commands, changes, 2, payload.data()), payload.size());

  fl::TickMeta m;
  hal::SensorFrame s;
  hal::CommandFrame c;
  std::size_t n = 0;
  ASSERT_TRUE(fl::decode_tick(payload.data(), payload.size(), m, s, c, n));
  EXPECT_FALSE(fl::decode_tick(payload.data(), payload.size() - 1, m, s, c, n));
  EXPECT_EQ(m.tick, 42);
  EXPECT_EQ(m.dropped_before, 5u);
  EXPECT_EQ(m.motion, MotionState::kWalk);
  EXPECT_TRUE(m.fallen);
  EXPECT_EQ(s.tick, 41);
  EXPECT_EQ(c.tick, 42);
  EXPECT_EQ(s.servos[3].load, as_logged(-0.3));
  EXPECT_EQ(s.servos[3].error_flags, hal::error_bits::kOverheating);
  EXPECT_EQ(s.servos[3].health, hal::DeviceHealth::kError);
  EXPECT_EQ(s.servos[0].torque_enabled, sensors.servos[0].torque_enabled);
  EXPECT_EQ(s.cm730.gyro_rad_s[1], as_logged(-0.2));
  EXPECT_EQ(s.cm730.buttons, 2);
  EXPECT_EQ(c.servos[7].position_rad, as_logged(0.123456789));
  EXPECT_EQ(c.servos[7].torque_limit, 0.75);
  EXPECT_TRUE(c.servos[7].torque_enable);
  EXPECT_FALSE(c.servos[6].torque_enable);
  ASSERT_EQ(n, 2u);
  EXPECT_EQ(fl::decode_param_change(payload.data(), 1).handle, 250u);
  EXPECT_EQ(fl::decode_param_change(payload.data(), 1).value, -1e-9);  // parameters: exact
}

TEST(FlightLogFormat, Crc32IsZlibs) {
  const std::string text = "123456789";
  EXPECT_EQ(fl::crc32(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()),
            0xCBF43926u);
}

// The firmware on the scripted HAL with a recorder attached.
struct RecordedLoop {
  explicit RecordedLoop(const std::filesystem::path& log, std::size_t buffer = 1U << 20,
                        int poll_ms = 2) {
    EXPECT_TRUE(Firmware::create({}, firmware));
    hal::ScriptedRobot::Options options;
    options.echo_commands = true;
    options.record_capacity = 0;
    robot = std::make_unique<hal::ScriptedRobot>(
        options, std::vector<hal::SensorFrame>{hal::ScriptedRobot::standing_frame()});
    RecorderOptions record;
    record.path = log;
    record.buffer_bytes = buffer;
    record.writer_poll_ms = poll_ms;
    const fl::HeaderInputs header{&firmware->params(),
                                  &firmware->servos(),
                                  ServoTable::default_path(),
                                  firmware->period_ns(),
                                  "test",
                                  "",
                                  &firmware->robot(),
                                  RobotDescription::default_path()};
    const Status s = FlightRecorder::open(record, header, firmware->controller(), recorder);
    EXPECT_TRUE(s) << s.message();
    loop = std::make_unique<ControlLoop>(*robot, firmware->controller(), firmware->params());
    loop->set_recorder(recorder.get());
  }
  std::unique_ptr<Firmware> firmware;
  std::unique_ptr<hal::ScriptedRobot> robot;
  std::unique_ptr<FlightRecorder> recorder;
  std::unique_ptr<ControlLoop> loop;
};

TEST(FlightRecorder, RecordsEveryTickAsTheLoopRanIt) {
  test::TempDir dir;
  const auto path = dir.path() / "run.flog";
  RecordedLoop run(path);
  run.loop->run(200);
  ASSERT_TRUE(run.firmware->params().stage({{"stand.gain", 50}, {"motion.fallen_gain", 6}}));
  run.loop->run(100);
  const RecorderTotals totals = run.recorder->close();
  EXPECT_EQ(totals.ticks_recorded, 300u);
  EXPECT_EQ(totals.ticks_dropped, 0u);
  EXPECT_EQ(totals.write_error, "");
  EXPECT_EQ(totals.bytes_written, std::filesystem::file_size(path));

  FlightLog log;
  ASSERT_TRUE(read_flight_log(path, log));
  EXPECT_TRUE(log.has_end);
  EXPECT_EQ(log.stopped_early, "");
  EXPECT_EQ(log.complete_bytes, log.file_bytes);
  EXPECT_EQ(log.header["format"], "stride-flight-log");
  EXPECT_EQ(log.header["hal"], "test");
  EXPECT_EQ(log.header["firmware"]["version"], std::string(fl::firmware_version()));
  EXPECT_EQ(log.header["robot_description"]["hash"],
            fl::robot_description_hash(run.firmware->servos(), run.firmware->robot()));
  EXPECT_EQ(log.header["servo_table"].size(), hal::kServoCount);
  EXPECT_EQ(log.header["servo_table"][19]["name"], run.firmware->servos()[19].name);
  ASSERT_EQ(log.header["parameters"].size(), run.firmware->params().size());
  const int gain = log.parameter_index("stand.gain");
  ASSERT_GE(gain, 0);
  EXPECT_EQ(log.header["parameters"][gain]["value"], 30.0);  // the value at start

  ASSERT_EQ(log.ticks.size(), 300u);
  for (std::size_t i = 0; i < log.ticks.size(); ++i) {
    EXPECT_EQ(log.ticks[i].meta.tick, static_cast<hal::Tick>(i));
    EXPECT_EQ(log.ticks[i].meta.dropped_before, 0u);
    EXPECT_EQ(log.ticks[i].param_changes.empty(), i != 200) << i;
  }
  // The batch is logged at the tick it was applied, both writes, and the commands of that very
  // tick already follow it (stand.gain 30 -> P 76, 50 -> 127).
  const auto& changed = log.ticks[200];
  ASSERT_EQ(changed.param_changes.size(), 2u);
  const int fallen_gain = log.parameter_index("motion.fallen_gain");
  for (const fl::ParamChange& change : changed.param_changes) {
    if (change.handle == static_cast<ParamHandle>(gain)) {
      EXPECT_EQ(change.value, 50.0);
    } else {
      EXPECT_EQ(change.handle, static_cast<ParamHandle>(fallen_gain));
      EXPECT_EQ(change.value, 6.0);
    }
  }
  EXPECT_EQ(log.ticks[199].commands.servos[0].p_gain, 76.0);
  EXPECT_EQ(changed.commands.servos[0].p_gain, 127.0);
  // The last tick is what the loop sent and read.
  const FlightLogTick& last = log.ticks.back();
  const hal::CommandFrame& sent = run.loop->last_commands();
  const hal::SensorFrame& read = run.loop->last_sensors();
  EXPECT_EQ(last.commands.tick, sent.tick);
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    EXPECT_EQ(last.commands.servos[i].position_rad, as_logged(sent.servos[i].position_rad)) << i;
    EXPECT_EQ(last.commands.servos[i].p_gain, as_logged(sent.servos[i].p_gain)) << i;
    EXPECT_EQ(last.commands.servos[i].torque_enable, sent.servos[i].torque_enable) << i;
    EXPECT_EQ(last.sensors.servos[i].position_rad, as_logged(read.servos[i].position_rad)) << i;
  }
  EXPECT_EQ(last.sensors.cm730.accel_mps2[2], as_logged(read.cm730.accel_mps2[2]));
  EXPECT_EQ(last.meta.motion, run.firmware->controller().motion().state());
}

TEST(FlightRecorder, TheRecordedLoopAllocatesNothing) {
  test::TempDir dir;
  RecordedLoop run(dir.path() / "run.flog");
  run.loop->run(5);  // warm-up: the writer thread has popped once
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_TRUE(run.firmware->params().stage({{"stand.gain", 50}}));
  test::start_counting_allocations();
  run.loop->run(500);  // counts this thread and the writer thread
  EXPECT_EQ(test::stop_counting_allocations(), 0u);
  EXPECT_EQ(run.recorder->close().ticks_dropped, 0u);
}

TEST(FlightRecorder, AFullRingDropsWholeTicksAndCountsThem) {
  test::TempDir dir;
  const auto path = dir.path() / "run.flog";
  // Room for two ticks; the writer looks at the ring once a second.
  const std::size_t two_ticks = 2 * (4 + fl::kTickFixedBytes) + 40;
  RecordedLoop run(path, two_ticks, 1000);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // the writer is asleep
  run.loop->run(20);  // 2 recorded, 18 dropped: the loop never waited for the writer
  ASSERT_TRUE(run.firmware->params().stage({{"stand.gain", 50}}));
  run.loop->run(5);  // dropped, with the parameter change
  EXPECT_EQ(run.recorder->dropped_ticks(), 23u);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // the writer drains the ring
  run.loop->run(5);                                              // 2 recorded, 3 dropped
  const RecorderTotals totals = run.recorder->close();
  EXPECT_EQ(totals.ticks_recorded, 4u);
  EXPECT_EQ(totals.ticks_dropped, 26u);

  FlightLog log;
  ASSERT_TRUE(read_flight_log(path, log));
  ASSERT_EQ(log.ticks.size(), 4u);
  EXPECT_EQ(log.ticks[1].meta.tick, 1);
  EXPECT_EQ(log.ticks[2].meta.tick, 25);
  EXPECT_EQ(log.ticks[2].meta.dropped_before, 23u);
  // The change applied at dropped tick 20 is carried into the next recorded tick.
  ASSERT_EQ(log.ticks[2].param_changes.size(), 1u);
  EXPECT_EQ(log.ticks[2].param_changes[0].handle,
            static_cast<ParamHandle>(log.parameter_index("stand.gain")));
  EXPECT_EQ(log.dropped_ticks(), 26u);
}

std::vector<char> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::filesystem::path& path, const std::vector<char>& bytes,
                 std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(size));
}

TEST(FlightLogReader, ACutOrDamagedLogReadsUpToItsLastCompleteBlock) {
  test::TempDir dir;
  const auto path = dir.path() / "run.flog";
  {
    RecordedLoop run(path);
    run.loop->run(10);
  }
  const std::vector<char> bytes = read_bytes(path);
  FlightLog whole;
  ASSERT_TRUE(read_flight_log(path, whole));
  ASSERT_EQ(whole.ticks.size(), 10u);
  const std::size_t block = 8 + fl::kTickFixedBytes + 4;
  const std::size_t end_block = 8 + whole.end.dump().size() + 4;
  const std::size_t first_tick = bytes.size() - end_block - 10 * block;

  const auto cut = dir.path() / "cut.flog";
  write_bytes(cut, bytes, bytes.size() - end_block - block / 2);  // killed while writing tick 9
  FlightLog log;
  ASSERT_TRUE(read_flight_log(cut, log));
  EXPECT_EQ(log.ticks.size(), 9u);
  EXPECT_FALSE(log.has_end);
  EXPECT_EQ(log.complete_bytes, first_tick + 9 * block);
  EXPECT_NE(log.stopped_early.find("incomplete block"), std::string::npos) << log.stopped_early;

  std::vector<char> damaged = bytes;
  damaged[first_tick + 4 * block + 100] ^= 0x10;  // a flipped bit in tick 4
  write_bytes(cut, damaged, damaged.size());
  ASSERT_TRUE(read_flight_log(cut, log));
  EXPECT_EQ(log.ticks.size(), 4u);
  EXPECT_NE(log.stopped_early.find("CRC mismatch"), std::string::npos) << log.stopped_early;

  write_bytes(cut, bytes, first_tick - 10);  // cut inside the header
  Status s = read_flight_log(cut, log);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("no complete header"), std::string::npos) << s.message();
  write_bytes(cut, std::vector<char>(100, 'x'), 100);
  s = read_flight_log(cut, log);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("not a Stride flight log"), std::string::npos) << s.message();
}

TEST(FlightRecorder, AnUnwritablePathIsNamed) {
  std::unique_ptr<Firmware> firmware;
  ASSERT_TRUE(Firmware::create({}, firmware));
  std::unique_ptr<FlightRecorder> recorder;
  RecorderOptions record;
  record.path = "/nonexistent-stride-dir/run.flog";
  const fl::HeaderInputs header{
      &firmware->params(), &firmware->servos(), "", 10'000'000, "test", "", &firmware->robot(), ""};
  const Status s = FlightRecorder::open(record, header, firmware->controller(), recorder);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(),
            "cannot open '/nonexistent-stride-dir/run.flog' for writing: No such file or "
            "directory");
}

}  // namespace
}  // namespace stride::fw
