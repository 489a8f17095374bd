// SimRobot: the HAL (hal::Robot) backed by a SimWorld, in lockstep.
//
// sleep_until(k) advances the physics to t_k = k * period in the calling thread (one
// SimWorld::advance_period() per tick), so the control loop and the simulation can never
// drift or deadlock. read() and write() exchange the same frames as the serial HAL: present
// positions quantised to encoder ticks, the CM730 IMU in the torso frame, written registers
// echoed back. Once the world has failed (WorldStatus), time no longer advances, the servos
// and the CM730 report kError and the world's failure_reason() says why.
#pragma once

#include <memory>

#include "stride/hal/robot.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {

class SimRobot final : public hal::Robot {
 public:
  /// Takes over `world`; its control period becomes the tick length.
  explicit SimRobot(std::unique_ptr<SimWorld> world);

  std::int64_t period_ns() const noexcept override;
  hal::Tick sleep_until(hal::Tick tick) noexcept override;
  void read(hal::SensorFrame& out) noexcept override;
  void write(const hal::CommandFrame& commands) noexcept override;
  void set_torque_enable(bool enabled) noexcept override;
  const hal::Diagnostics& diagnostics() const noexcept override { return diagnostics_; }

  /// Gives the world back (to restart it for another episode); the robot is then unusable.
  std::unique_ptr<SimWorld> release_world() { return std::move(world_); }

  SimWorld& world() { return *world_; }
  const SimWorld& world() const { return *world_; }
  hal::Tick current_tick() const { return tick_; }

 private:
  std::unique_ptr<SimWorld> world_;
  hal::Tick tick_ = 0;
  hal::Diagnostics diagnostics_{};
};

}  // namespace stride::sim
