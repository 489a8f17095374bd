// DynamixelRobot's per-tick calls (read, write, set_torque_enable, diagnostics) allocate nothing
// after start-up, with and without faults (the in-process virtual bus allocates nothing either).
#include <gtest/gtest.h>

#include "counting_allocator.hpp"
#include "stride/firmware/dynamixel_config.hpp"
#include "stride/hal/dynamixel/dynamixel_robot.hpp"
#include "stride/hal/dynamixel/virtual_bus.hpp"
#include "stride/hal/dynamixel/virtual_bus_stream.hpp"

namespace stride::hal::dxl {
namespace {

TEST(DynamixelRobotAllocation, TicksAllocateNothing) {
  const auto& table = fw::ServoTable::defaults();
  VirtualBus::Options bus_options;
  bus_options.calibration = fw::servo_calibrations(table);
  bus_options.lockstep = true;
  bus_options.faults.drop_probability = 0.05;
  bus_options.faults.corrupt_probability = 0.05;
  bus_options.faults.silent[7] = true;
  bus_options.faults.start_after_cycles = 5;
  FirstOrderPhysics::Options physics;
  for (std::size_t i = 0; i < kServoCount; ++i)
    physics.models[i] = bus_options.calibration[i].model;
  VirtualBus bus(bus_options, std::make_unique<FirstOrderPhysics>(physics));
  std::unique_ptr<DynamixelRobot> robot;
  auto options = fw::dynamixel_options(table, 10'000'000);
  options.self_paced = false;  // no real sleeping in a unit test
  ASSERT_TRUE(
      DynamixelRobot::create(std::make_unique<VirtualBusStream>(bus, 1'000'000), options, robot)
          .is_ok());
  SensorFrame frame;
  CommandFrame command;
  for (auto& s : command.servos) s.torque_enable = true;
  stride::test::start_counting_allocations();
  for (Tick t = 0; t < 300; ++t) {
    for (auto& s : command.servos) s.position_rad = 0.001 * static_cast<double>(t);
    command.servos[3].d_gain = static_cast<double>(t % 3);
    command.tick = t;
    (void)robot->sleep_until(t);
    robot->read(frame);
    robot->write(command);
    if (t == 150) robot->set_torque_enable(false);
    (void)robot->diagnostics();
  }
  EXPECT_EQ(stride::test::stop_counting_allocations(), 0U);
  EXPECT_EQ(frame.servos[6].health, DeviceHealth::kMissing);  // the faults did happen
}

}  // namespace
}  // namespace stride::hal::dxl
