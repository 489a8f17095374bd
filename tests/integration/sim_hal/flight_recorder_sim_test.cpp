// stride-fw --hal sim --record: the log of a lockstep run holds exactly the frames of the same
// run made in process (the loop is deterministic), tick by tick and in the final state.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "stride/core/cli_args.hpp"
#include "stride/firmware/control_loop.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_cli.hpp"
#include "stride/sim_hal/sim_robot.hpp"
#include "temp_dir.hpp"

namespace stride::sim {
namespace {

const std::string kBin = STRIDE_BIN_DIR;
constexpr int kTicks = 300;

float as_logged(double value) {
  return static_cast<float>(value);
}

TEST(FlightRecorderSim, TheLogHoldsTheFramesTheLoopRan) {
  test::TempDir dir;
  const auto log_path = dir.path() / "sim.flog";
  const int code = test::wait_exit(
      test::spawn({kBin + "/stride-fw", "--hal", "sim", "--ticks", std::to_string(kTicks), "--seed",
                   "5", "--json", "--record", log_path.string()},
                  dir.path() / "out", dir.path() / "err"));
  ASSERT_EQ(code, 0) << test::slurp(dir.path() / "err");
  const auto report = nlohmann::json::parse(test::slurp(dir.path() / "out"));
  EXPECT_EQ(report["record"]["ticks_dropped"], 0);

  // The same run in process: the same world options as stride-fw parses them.
  core::CliArgs args;
  declare_world_options(args);
  const char* argv[] = {"x", "--seed", "5"};
  ASSERT_TRUE(args.parse(3, argv));
  WorldOptions options;
  ASSERT_TRUE(read_world_options(args, options));
  std::unique_ptr<fw::Firmware> firmware;
  ASSERT_TRUE(fw::Firmware::create({}, firmware));
  options.control_period_ns = firmware->period_ns();
  std::unique_ptr<SimWorld> world;
  ASSERT_TRUE(SimWorld::create(options, world));
  SimRobot robot(std::move(world));
  fw::ControlLoop loop(robot, firmware->controller(), firmware->params());
  loop.run(kTicks);
  ASSERT_EQ(report["sim"]["state_hash"], hash_hex(robot.world().state_hash()))
      << "stride-fw and the in-process run differ: the comparison below would mean nothing";

  fw::FlightLog log;
  const Status s = fw::read_flight_log(log_path, log);
  ASSERT_TRUE(s) << s.message();
  EXPECT_TRUE(log.has_end);
  EXPECT_EQ(log.header["hal"], "sim");
  ASSERT_EQ(log.ticks.size(), static_cast<std::size_t>(kTicks));
  for (std::size_t i = 0; i < log.ticks.size(); ++i) {
    ASSERT_EQ(log.ticks[i].meta.tick, static_cast<hal::Tick>(i));
    ASSERT_EQ(log.ticks[i].sensors.tick, static_cast<hal::Tick>(i));
  }
  const fw::FlightLogTick& last = log.ticks.back();
  const hal::CommandFrame& sent = loop.last_commands();
  const hal::SensorFrame& read = loop.last_sensors();
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    const auto& c = last.commands.servos[i];
    EXPECT_EQ(c.position_rad, as_logged(sent.servos[i].position_rad)) << i;
    EXPECT_EQ(c.moving_speed_rad_s, as_logged(sent.servos[i].moving_speed_rad_s)) << i;
    EXPECT_EQ(c.p_gain, as_logged(sent.servos[i].p_gain)) << i;
    EXPECT_EQ(c.torque_limit, as_logged(sent.servos[i].torque_limit)) << i;
    EXPECT_EQ(c.torque_enable, sent.servos[i].torque_enable) << i;
    const auto& r = last.sensors.servos[i];
    EXPECT_EQ(r.position_rad, as_logged(read.servos[i].position_rad)) << i;
    EXPECT_EQ(r.speed_rad_s, as_logged(read.servos[i].speed_rad_s)) << i;
    EXPECT_EQ(r.load, as_logged(read.servos[i].load)) << i;
    EXPECT_EQ(r.voltage_v, as_logged(read.servos[i].voltage_v)) << i;
    EXPECT_EQ(r.temperature_c, as_logged(read.servos[i].temperature_c)) << i;
    EXPECT_EQ(r.health, read.servos[i].health) << i;
  }
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(last.sensors.cm730.accel_mps2[k], as_logged(read.cm730.accel_mps2[k])) << k;
    EXPECT_EQ(last.sensors.cm730.gyro_rad_s[k], as_logged(read.cm730.gyro_rad_s[k])) << k;
  }
  EXPECT_EQ(last.meta.motion, firmware->controller().motion().state());
  EXPECT_EQ(log.header["motion_states"][static_cast<int>(last.meta.motion)],
            report["motion_state"]);
  EXPECT_NEAR(last.sensors.cm730.accel_mps2[2], 9.81, 1.0);  // standing: gravity on z
}

}  // namespace
}  // namespace stride::sim
