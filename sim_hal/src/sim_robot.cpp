// SimRobot: lockstep HAL over SimWorld.
#include "stride/sim_hal/sim_robot.hpp"

namespace stride::sim {

SimRobot::SimRobot(std::unique_ptr<SimWorld> world) : world_(std::move(world)) {
  for (hal::DeviceDiagnostics& d : diagnostics_.devices) d.health = hal::DeviceHealth::kOk;
}

std::int64_t SimRobot::period_ns() const noexcept {
  return world_->options().control_period_ns;
}

hal::Tick SimRobot::sleep_until(hal::Tick tick) noexcept {
  while (tick_ < tick) {
    if (!world_->advance_period()) {
      // A failed world no longer advances; report the tick so the loop does not spin.
      tick_ = tick;
      break;
    }
    ++tick_;
  }
  return tick_;
}

void SimRobot::read(hal::SensorFrame& out) noexcept {
  const bool ok = world_->status() == WorldStatus::kRunning;
  const hal::DeviceHealth health = ok ? hal::DeviceHealth::kOk : hal::DeviceHealth::kError;
  out.tick = tick_;
  for (std::size_t i = 0; i < hal::kServoCount; ++i) {
    out.servos[i] = world_->servo_state(i);
    out.servos[i].health = health;
    hal::DeviceDiagnostics& d = diagnostics_.devices[i];
    d.health = health;
    if (ok) {
      ++d.replies;
      d.consecutive_failures = 0;
    } else {
      ++d.error_replies;
      ++d.consecutive_failures;
    }
  }
  const ImuReading& imu = world_->imu();
  for (int k = 0; k < 3; ++k) {
    out.cm730.accel_mps2[static_cast<std::size_t>(k)] = imu.accel[k];
    out.cm730.gyro_rad_s[static_cast<std::size_t>(k)] = imu.gyro[k];
    out.cm730.mag_gauss[static_cast<std::size_t>(k)] = imu.mag[k];
  }
  out.cm730.has_magnetometer = imu.has_mag;
  out.cm730.voltage_v = world_->battery_voltage();
  out.cm730.buttons = 0;
  out.cm730.error_flags = 0;
  out.cm730.health = health;
  diagnostics_.devices[hal::Diagnostics::kCm730DiagIndex].health = health;
  ++diagnostics_.cycles;
}

void SimRobot::write(const hal::CommandFrame& commands) noexcept {
  for (std::size_t i = 0; i < hal::kServoCount; ++i)
    world_->set_servo_command(i, commands.servos[i]);
}

void SimRobot::set_torque_enable(bool enabled) noexcept {
  world_->set_torque_enable(enabled);
}

}  // namespace stride::sim
