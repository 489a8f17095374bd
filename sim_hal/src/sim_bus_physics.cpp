// SimBusPhysics implementation.
#include "stride/sim_hal/sim_bus_physics.hpp"

namespace stride::sim {

SimBusPhysics::SimBusPhysics(std::unique_ptr<SimWorld> world) : robot_(std::move(world)) {
  robot_.read(sensors_);  // the servos report the reset pose before the first command
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    commands_.servos[i].position_rad = sensors_.servos[i].position_rad;
  }
}

void SimBusPhysics::set_command(std::size_t index, const hal::dxl::PhysicsServoCommand& command) {
  if (index >= hal::kServoCount) return;
  hal::ServoCommand& c = commands_.servos[index];
  c.position_rad = command.goal_rad;
  c.moving_speed_rad_s = command.speed_limit_rad_s;
  c.p_gain = command.p_gain;
  c.torque_limit = command.torque_limit;
  c.torque_enable = command.torque_enabled;
}

void SimBusPhysics::advance(double dt_s) {
  const double period_s = static_cast<double>(robot_.period_ns()) * 1e-9;
  pending_s_ += dt_s;
  // Tolerance: a lockstep caller passes exactly one period, which must give one tick.
  while (pending_s_ >= period_s * (1.0 - 1e-9)) {
    pending_s_ -= period_s;
    robot_.write(commands_);
    robot_.sleep_until(robot_.current_tick() + 1);
    robot_.read(sensors_);
  }
}

hal::dxl::PhysicsServoState SimBusPhysics::servo_state(std::size_t index) const {
  hal::dxl::PhysicsServoState state;
  if (index >= hal::kServoCount) return state;
  const hal::ServoState& s = sensors_.servos[index];
  state.position_rad = s.position_rad;
  state.speed_rad_s = s.speed_rad_s;
  state.load = s.load;
  state.temperature_c = s.temperature_c;
  state.voltage_v = s.voltage_v;
  return state;
}

hal::dxl::PhysicsImu SimBusPhysics::imu() const {
  hal::dxl::PhysicsImu imu;
  imu.accel_mps2 = sensors_.cm730.accel_mps2;
  imu.gyro_rad_s = sensors_.cm730.gyro_rad_s;
  imu.mag_gauss = sensors_.cm730.mag_gauss;
  return imu;
}

}  // namespace stride::sim
