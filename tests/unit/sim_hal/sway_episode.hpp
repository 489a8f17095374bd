// A short swaying-Stand episode for the SimWorld determinism tests: `periods` control periods of
// the Stand pose with every servo swaying by 0.05 rad at P 76. Returns the final state hash and
// the sum of the accelerometer's x readings (the reset's noise and biases show there).
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>

#include "stride/sim_hal/sim_robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim::test {

inline std::pair<std::uint64_t, double> sway(std::unique_ptr<SimWorld> world, int periods) {
  SimRobot robot(std::move(world));
  hal::SensorFrame sensors;
  double accel_sum = 0.0;
  for (hal::Tick k = 1; k <= periods; ++k) {
    robot.sleep_until(k);
    robot.read(sensors);
    accel_sum += sensors.cm730.accel_mps2[0];
    hal::CommandFrame frame;
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      frame.servos[i].position_rad =
          igus_stand_pose()[i] + 0.05 * std::sin(0.1 * static_cast<double>(k));
      frame.servos[i].p_gain = 76;
      frame.servos[i].torque_enable = true;
    }
    robot.write(frame);
  }
  return {robot.world().state_hash(), accel_sum};
}

}  // namespace stride::sim::test
