// SimBusPhysics: the Simbody world behind the virtual Dynamixel bus, so that an unmodified
// stride-fw with the serial HAL drives the simulated robot over the wire protocol
// (`stride vbus --link PATH --sim`).
//
// The virtual bus turns each SYNC_WRITE into per-servo commands (set_command) and, in lockstep
// mode, calls advance(period) once per BULK_READ: this writes the commands into the SimRobot
// and advances the world by exactly one control period, then samples the sensors that the
// BULK_READ reply carries. A dt that is not a whole number of periods is accumulated, so the
// wall-clock mode also advances in whole periods.
#pragma once

#include <memory>

#include "stride/hal/command_frame.hpp"
#include "stride/hal/dynamixel/virtual_bus_physics.hpp"
#include "stride/hal/sensor_frame.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace stride::sim {

class SimBusPhysics final : public hal::dxl::VirtualBusPhysics {
 public:
  explicit SimBusPhysics(std::unique_ptr<SimWorld> world);

  void set_command(std::size_t index, const hal::dxl::PhysicsServoCommand& command) override;
  void advance(double dt_s) override;
  hal::dxl::PhysicsServoState servo_state(std::size_t index) const override;
  hal::dxl::PhysicsImu imu() const override;

  const SimWorld& world() const { return robot_.world(); }
  /// Control periods simulated so far.
  hal::Tick ticks() const { return robot_.current_tick(); }

 private:
  SimRobot robot_;
  hal::CommandFrame commands_{};
  hal::SensorFrame sensors_{};
  double pending_s_ = 0.0;
};

}  // namespace stride::sim
