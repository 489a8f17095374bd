// stride-fw --hal serial --record against the virtual bus of `stride vbus` on a pseudo-terminal:
// every tick is in the log, the servos answered, and the goal each servo was given (as the HAL
// reports it in the next tick's SensorFrame, encoder-quantised) is what the log says was sent.
#include <signal.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "temp_dir.hpp"

namespace {

const std::string kBin = STRIDE_BIN_DIR;
using stride::test::slurp;
using stride::test::spawn;
using stride::test::wait_exit;

TEST(FlightRecorderSerial, RecordsTheSerialHalAgainstTheVirtualBus) {
  stride::test::TempDir dir;
  const auto link = dir.path() / "bus";
  const pid_t vbus = spawn({kBin + "/stride", "vbus", "--link", link.string(), "--json"},
                           dir.path() / "vbus.out", dir.path() / "vbus.err");
  for (int i = 0; i < 200 && !std::filesystem::exists(link); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(std::filesystem::exists(link)) << slurp(dir.path() / "vbus.err");
  const auto log_path = dir.path() / "serial.flog";
  const int code =
      wait_exit(spawn({kBin + "/stride-fw", "--hal", "serial", "--port", link.string(), "--ticks",
                       "300", "--bus-margin-us", "4000", "--json", "--record", log_path.string()},
                      dir.path() / "fw.out", dir.path() / "fw.err"));
  kill(vbus, SIGINT);
  (void)wait_exit(vbus);
  ASSERT_EQ(code, 0) << slurp(dir.path() / "fw.err");
  const auto report = nlohmann::json::parse(slurp(dir.path() / "fw.out"));

  stride::fw::FlightLog log;
  const stride::Status s = stride::fw::read_flight_log(log_path, log);
  ASSERT_TRUE(s) << s.message();
  EXPECT_TRUE(log.has_end);
  EXPECT_EQ(log.header["hal"], "serial");
  EXPECT_EQ(log.dropped_ticks(), 0u);
  ASSERT_EQ(log.ticks.size(), report["cycles"].get<std::size_t>());
  ASSERT_EQ(log.ticks.size(), 300u);
  // Gaps between logged ticks are the loop's overruns (ticks skipped, not caught up); the
  // report counts each such tick once in the loop and once more in RealtimeRobot, so it may
  // say up to twice as many.
  const auto gaps = log.ticks.back().meta.tick - log.ticks.front().meta.tick + 1 - 300;
  EXPECT_LE(gaps, report["missed_ticks"].get<long>());

  const double encoder_tick = 2 * std::numbers::pi / 4096;
  std::size_t answered = 0, compared = 0;
  for (std::size_t k = 1; k < log.ticks.size(); ++k) {
    const auto& before = log.ticks[k - 1];
    const auto& now = log.ticks[k];
    for (std::size_t i = 0; i < stride::hal::kServoCount; ++i) {
      if (now.sensors.servos[i].health != stride::hal::DeviceHealth::kOk) continue;
      ++answered;
      EXPECT_GT(now.sensors.servos[i].voltage_v, 5.0) << k << " " << i;
      if (!before.commands.servos[i].torque_enable) continue;
      ++compared;
      EXPECT_NEAR(now.sensors.servos[i].goal_position_rad, before.commands.servos[i].position_rad,
                  encoder_tick)
          << "tick " << now.meta.tick << " servo " << i + 1;
    }
  }
  // A pty's latency is the OS scheduler's: on a loaded machine replies time out, so the bus
  // need only have worked; the log must agree with the HAL's own count of replies exactly.
  EXPECT_GE(answered, 299u * 20u / 2u) << "servos answered in fewer than half the ticks";
  EXPECT_GT(compared, 100u * 20u);
  const auto& devices = report["bus"]["devices"];
  ASSERT_EQ(devices.size(), stride::hal::kServoCount + 1);
  for (std::size_t d = 0; d < devices.size(); ++d) {
    std::uint64_t replied = 0;
    for (const auto& tick : log.ticks) {
      const auto health =
          d < stride::hal::kServoCount ? tick.sensors.servos[d].health : tick.sensors.cm730.health;
      if (health == stride::hal::DeviceHealth::kOk || health == stride::hal::DeviceHealth::kError) {
        ++replied;
      }
    }
    EXPECT_EQ(replied, devices[d]["replies"].get<std::uint64_t>()) << devices[d]["name"];
  }
  // The last tick's servos stand where the loop told them to (first-order servo model).
  for (std::size_t i = 0; i < stride::hal::kServoCount; ++i) {
    if (log.ticks.back().sensors.servos[i].health != stride::hal::DeviceHealth::kOk) continue;
    EXPECT_NEAR(log.ticks.back().sensors.servos[i].position_rad,
                log.ticks.back().commands.servos[i].position_rad, 0.05)
        << i;
  }
}

}  // namespace
