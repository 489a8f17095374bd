// DynamixelRobot against the in-process virtual bus: start-up checks, per-tick SYNC_WRITE of
// only what changed, BULK_READ into the SensorFrame, and the bounded failure policy.
#include <gtest/gtest.h>

#include <cmath>

#include "stride/firmware/dynamixel_config.hpp"
#include "stride/hal/dynamixel/dynamixel_robot.hpp"
#include "stride/hal/dynamixel/virtual_bus.hpp"
#include "stride/hal/dynamixel/virtual_bus_stream.hpp"

namespace stride::hal::dxl {
namespace {

struct Rig {
  explicit Rig(VirtualBusFaults faults = {}, bool allow_missing = false,
               std::int64_t period_ns = 10'000'000) {
    const auto& table = fw::ServoTable::defaults();
    VirtualBus::Options bus_options;
    bus_options.calibration = fw::servo_calibrations(table);
    bus_options.lockstep = true;
    bus_options.faults = faults;
    FirstOrderPhysics::Options physics;
    for (std::size_t i = 0; i < kServoCount; ++i)
      physics.models[i] = bus_options.calibration[i].model;
    bus = std::make_unique<VirtualBus>(bus_options, std::make_unique<FirstOrderPhysics>(physics));
    options = fw::dynamixel_options(table, period_ns);
    options.allow_missing = allow_missing;
    status =
        DynamixelRobot::create(std::make_unique<VirtualBusStream>(*bus, 1'000'000), options, robot);
  }
  CommandFrame hold(double angle = 0.1) {
    CommandFrame c;
    for (auto& s : c.servos) {
      s.position_rad = angle;
      s.torque_enable = true;
      s.p_gain = 32;
    }
    return c;
  }
  std::unique_ptr<VirtualBus> bus;
  DynamixelRobot::Options options;
  std::unique_ptr<DynamixelRobot> robot;
  Status status;
};

TEST(DynamixelRobot, StartsUpAndSetsReturnDelayAndStatusLevel) {
  Rig rig;
  ASSERT_TRUE(rig.status.is_ok()) << rig.status.message();
  EXPECT_EQ(rig.robot->startup_report(), "21 of 21 devices found");
  for (std::uint8_t id = 1; id <= 20; ++id) {
    EXPECT_EQ(rig.bus->peek(id, 5), 0) << int(id);   // return delay 0
    EXPECT_EQ(rig.bus->peek(id, 16), 1) << int(id);  // status return level 1
  }
  EXPECT_EQ(rig.bus->peek(kCm730Id, 24), 1);  // Dynamixel power on
}

TEST(DynamixelRobot, FollowsCommandsAndReadsEveryDevice) {
  Rig rig;
  ASSERT_TRUE(rig.status.is_ok()) << rig.status.message();
  SensorFrame frame;
  CommandFrame command = rig.hold(0.2);
  for (Tick t = 0; t < 100; ++t) {
    rig.robot->read(frame);
    command.tick = t;
    rig.robot->write(command);
  }
  rig.robot->read(frame);
  for (std::size_t i = 0; i < kServoCount; ++i) {
    EXPECT_EQ(frame.servos[i].health, DeviceHealth::kOk) << i;
    EXPECT_NEAR(frame.servos[i].position_rad, 0.2, 0.01) << rig.options.names[i];
    EXPECT_NEAR(frame.servos[i].voltage_v, 15.0, 1e-9);
    EXPECT_TRUE(frame.servos[i].torque_enabled);
  }
  EXPECT_EQ(frame.cm730.health, DeviceHealth::kOk);
  EXPECT_NEAR(frame.cm730.accel_mps2[2], 9.80665, 1e-9);
  const auto& d = rig.robot->diagnostics();
  EXPECT_EQ(d.cycles, 100U);
  for (const auto& dev : d.devices) {
    EXPECT_EQ(dev.timeouts, 0U);
    EXPECT_EQ(dev.corrupt_replies, 0U);
  }
  EXPECT_EQ(rig.robot->health_report(), "");
}

TEST(DynamixelRobot, SyncWriteCarriesOnlyChangedServos) {
  Rig rig;
  ASSERT_TRUE(rig.status.is_ok());
  CommandFrame command = rig.hold(0.0);
  command.tick = 1;
  rig.robot->write(command);  // first write: all 20 servos + torque enable
  std::uint64_t before = rig.robot->diagnostics().bytes_tx;
  command.tick = 2;
  rig.robot->write(command);  // nothing changed: nothing sent
  EXPECT_EQ(rig.robot->diagnostics().bytes_tx, before);
  command.servos[4].position_rad = 0.5;
  command.servos[9].p_gain = 40;
  command.tick = 3;
  rig.robot->write(command);
  // One SYNC_WRITE from P gain with 2 records: 6 + 2 + 2 * 9 = 26 bytes.
  EXPECT_EQ(rig.robot->diagnostics().bytes_tx - before, 26U);
  EXPECT_EQ(rig.bus->peek(10, 28), 40);
  EXPECT_EQ(rig.bus->peek(5, 30) | (rig.bus->peek(5, 31) << 8),
            units::position_to_ticks(0.5, rig.options.calibration[4]));
  // A D gain change goes in its own 2-byte SYNC_WRITE: 6 + 2 + 3 = 11 bytes.
  before = rig.robot->diagnostics().bytes_tx;
  command.servos[2].d_gain = 8;
  command.tick = 4;
  rig.robot->write(command);
  EXPECT_EQ(rig.robot->diagnostics().bytes_tx - before, 11U);
  EXPECT_EQ(rig.bus->peek(3, 26), 8);
}

TEST(DynamixelRobot, NamesMissingDevicesAtStartUp) {
  VirtualBusFaults faults;
  faults.silent[7] = true;
  faults.silent[kCm730Id] = true;
  Rig rig(faults);
  ASSERT_FALSE(rig.status.is_ok());
  EXPECT_NE(rig.status.message().find("7 r_hip_yaw"), std::string::npos) << rig.status.message();
  EXPECT_NE(rig.status.message().find("200 CM730"), std::string::npos);
}

TEST(DynamixelRobot, SilentServoIsBlamedSkippedAndDoesNotSilenceOthers) {
  VirtualBusFaults faults;
  faults.silent[7] = true;
  faults.start_after_cycles = 10;
  Rig rig(faults, false, 1'000'000);  // 1 ms ticks keep the test short
  ASSERT_TRUE(rig.status.is_ok()) << rig.status.message();
  SensorFrame frame;
  CommandFrame command = rig.hold(0.0);
  for (Tick t = 0; t < 200; ++t) {
    (void)rig.robot->sleep_until(t);
    rig.robot->read(frame);
    command.tick = t;
    rig.robot->write(command);
  }
  EXPECT_EQ(frame.servos[6].health, DeviceHealth::kMissing);
  for (std::size_t i = 0; i < kServoCount; ++i) {
    if (i != 6) {
      EXPECT_EQ(frame.servos[i].health, DeviceHealth::kOk) << i;
    }
  }
  const auto& d = rig.robot->diagnostics();
  EXPECT_GE(d.devices[6].timeouts, 5U);
  EXPECT_EQ(d.devices[6].replies, 10U);
  EXPECT_NE(rig.robot->health_report().find("7 r_hip_yaw"), std::string::npos);
}

TEST(DynamixelRobot, OverheatingServoReportsErrorFlags) {
  VirtualBusFaults faults;
  faults.overheat[13] = true;
  Rig rig(faults);
  ASSERT_TRUE(rig.status.is_ok());
  SensorFrame frame;
  rig.robot->read(frame);
  EXPECT_EQ(frame.servos[12].health, DeviceHealth::kError);
  EXPECT_NE(frame.servos[12].error_flags & error_bits::kOverheating, 0);
  EXPECT_DOUBLE_EQ(frame.servos[12].temperature_c, 85.0);
  EXPECT_EQ(frame.servos[11].health, DeviceHealth::kOk);
}

TEST(DynamixelRobot, DroppedAndCorruptedRepliesAreCountedPerDevice) {
  VirtualBusFaults faults;
  faults.drop_probability = 0.02;
  faults.corrupt_probability = 0.02;
  faults.start_after_cycles = 1;
  Rig rig(faults);
  ASSERT_TRUE(rig.status.is_ok());
  SensorFrame frame;
  CommandFrame command = rig.hold(0.0);
  for (Tick t = 0; t < 500; ++t) {
    rig.robot->read(frame);
    command.tick = t;
    rig.robot->write(command);
  }
  std::uint64_t timeouts = 0;
  std::uint64_t corrupt = 0;
  std::uint64_t replies = 0;
  for (const auto& dev : rig.robot->diagnostics().devices) {
    timeouts += dev.timeouts;
    corrupt += dev.corrupt_replies;
    replies += dev.replies;
  }
  const auto& c = rig.bus->counters();
  EXPECT_GT(c.dropped, 0U);
  EXPECT_GT(c.corrupted, 0U);
  EXPECT_EQ(timeouts + corrupt, c.dropped + c.corrupted);  // every injected fault is counted
  EXPECT_GT(replies, 500U * 21U * 9U / 10U);
}

TEST(DynamixelRobot, WrongModelIsNamed) {
  const auto& table = fw::ServoTable::defaults();
  VirtualBus::Options bus_options;
  bus_options.calibration = fw::servo_calibrations(table);
  bus_options.calibration[0].model = ServoModelId::kMx106;  // the bus has an MX-106 at ID 1
  FirstOrderPhysics::Options physics;
  auto bus =
      std::make_unique<VirtualBus>(bus_options, std::make_unique<FirstOrderPhysics>(physics));
  auto options = fw::dynamixel_options(table, 10'000'000);
  std::unique_ptr<DynamixelRobot> robot;
  const Status s =
      DynamixelRobot::create(std::make_unique<VirtualBusStream>(*bus, 1'000'000), options, robot);
  ASSERT_FALSE(s.is_ok());
  EXPECT_NE(s.message().find("1 r_shoulder_pitch is MX-106 (320), servo table says MX-64 (310)"),
            std::string::npos)
      << s.message();
}

}  // namespace
}  // namespace stride::hal::dxl

namespace stride::hal::dxl {
namespace {

// Lockstep virtual bus + seeded faults: two runs give identical frames and counters.
TEST(DynamixelRobot, LockstepRunsWithSeededFaultsAreDeterministic) {
  auto run = [] {
    VirtualBusFaults faults;
    faults.drop_probability = 0.05;
    faults.corrupt_probability = 0.05;
    faults.seed = 42;
    Rig rig(faults);
    SensorFrame frame;
    CommandFrame command = rig.hold(0.3);
    std::vector<double> trace;
    for (Tick t = 0; t < 200; ++t) {
      rig.robot->read(frame);
      trace.push_back(frame.servos[10].position_rad);
      command.tick = t;
      rig.robot->write(command);
    }
    std::vector<std::uint32_t> counters;
    for (const auto& d : rig.robot->diagnostics().devices) {
      counters.push_back(d.replies);
      counters.push_back(d.timeouts);
      counters.push_back(d.corrupt_replies);
    }
    return std::make_pair(trace, counters);
  };
  const auto a = run();
  const auto b = run();
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second, b.second);
  EXPECT_NEAR(a.first.back(), 0.3, 0.01);
}

}  // namespace
}  // namespace stride::hal::dxl
