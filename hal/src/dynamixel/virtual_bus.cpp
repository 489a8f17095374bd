// Emulated Dynamixel 1.0 bus: MX servos and the CM730 (see virtual_bus.hpp).
#include "stride/hal/dynamixel/virtual_bus.hpp"

#include <cmath>
#include <cstdlib>

#include "stride/hal/dynamixel/codec_v1.hpp"

namespace stride::hal::dxl {

VirtualBus::VirtualBus(const Options& options, std::unique_ptr<VirtualBusPhysics> physics)
    : VirtualBusCore({options.calibration, options.lockstep, options.period_ns, options.faults},
                     Layout{.protocol = Protocol::kV1,
                            .id = mx1::kId,
                            .return_delay = mx1::kReturnDelayTime,
                            .status_return_level = mx1::kStatusReturnLevel,
                            .registered = mx1::kRegistered,
                            .unanswered_ends_chain = true},
                     std::move(physics)),
      cm730_profile_(options.cm730_profile) {
  for (std::size_t i = 0; i < kServoCount; ++i) {
    Device d;
    d.id = static_cast<std::uint8_t>(i + 1);
    d.servo_index = static_cast<int>(i);
    d.table = calibration_[i].model == ServoModelId::kMx64 ? &mx64_v1_table() : &mx106_v1_table();
    devices_.push_back(std::move(d));
  }
  Device cm;
  cm.id = kCm730Id;
  cm.table = &cm730_table(cm730_profile_);
  devices_.push_back(std::move(cm));
  for (Device& d : devices_) {
    reset_device(d);
    refresh(d);
  }
  start_clock();
}

void VirtualBus::reset_device(Device& device) {
  const std::uint8_t id = device.id;
  device.mem.fill(0);
  for (const Register& r : device.table->registers) store(device.mem, r.address, r.size, r.initial);
  device.mem[mx1::kId] = id;  // RESET keeps the ID here so the emulated bus stays addressable
  if (device.servo_index >= 0) {
    const std::size_t i = static_cast<std::size_t>(device.servo_index);
    const auto ticks =
        units::position_to_ticks(physics().servo_state(i).position_rad, calibration_[i]);
    store(device.mem, mx1::kGoalPosition, 2, ticks);
    push_command(device);
  }
  device.registered = false;
}

std::uint8_t VirtualBus::peek(std::uint8_t id, std::uint8_t address) const {
  const Device* d = find(id);
  return d != nullptr ? d->mem[address] : 0;
}

void VirtualBus::push_command(Device& device) {
  if (device.servo_index < 0) return;
  const std::size_t i = static_cast<std::size_t>(device.servo_index);
  const ServoCalibration& cal = calibration_[i];
  PhysicsServoCommand c;
  c.goal_rad = units::ticks_to_position(
      static_cast<std::uint16_t>(load(device.mem, mx1::kGoalPosition, 2)), cal);
  c.speed_limit_rad_s = units::moving_speed_from_register(
      static_cast<std::uint16_t>(load(device.mem, mx1::kMovingSpeed, 2)));
  c.p_gain = device.mem[mx1::kPGain];
  c.torque_limit = units::torque_limit_from_register(
      static_cast<std::uint16_t>(load(device.mem, mx1::kTorqueLimit, 2)));
  c.torque_enabled = device.mem[mx1::kTorqueEnable] != 0;
  command(device, c);
}

// The CM730's IMU (and magnetometer, NimbRo's firmware) and voltage.
void VirtualBus::refresh_cm730(Device& device) {
  const PhysicsImu imu = physics().imu();
  if (cm730_profile_ == Cm730Profile::kNimbro) {
    namespace n = cm730_nimbro;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto offset = static_cast<std::uint16_t>(2 * k);
      store(device.mem, n::kGyroX + offset, 2, units::nimbro_gyro_to_raw(imu.gyro_rad_s[k]));
      store(device.mem, n::kAccelX + offset, 2, units::nimbro_accel_to_raw(imu.accel_mps2[k]));
      store(device.mem, n::kMagX + offset, 2, units::nimbro_mag_to_raw(imu.mag_gauss[k]));
    }
    device.mem[n::kBatteryVoltage] = units::voltage_to_register(15.0);
    return;
  }
  store(device.mem, cm730::kAccelX, 2, units::accel_to_raw(imu.accel_mps2[0]));
  store(device.mem, cm730::kAccelY, 2, units::accel_to_raw(imu.accel_mps2[1]));
  store(device.mem, cm730::kAccelZ, 2, units::accel_to_raw(imu.accel_mps2[2]));
  store(device.mem, cm730::kGyroX, 2, units::gyro_to_raw(imu.gyro_rad_s[0]));
  store(device.mem, cm730::kGyroY, 2, units::gyro_to_raw(imu.gyro_rad_s[1]));
  store(device.mem, cm730::kGyroZ, 2, units::gyro_to_raw(imu.gyro_rad_s[2]));
  device.mem[cm730::kVoltage] = units::voltage_to_register(15.0);
}

// Present values from the physics; hardware error bits; alarm shutdown.
void VirtualBus::refresh(Device& device) {
  if (device.servo_index < 0) {
    refresh_cm730(device);
    return;
  }
  const ServoCalibration& cal = calibration_[static_cast<std::size_t>(device.servo_index)];
  const PhysicsServoState s = servo_state(device);
  store(device.mem, mx1::kPresentPosition, 2, units::position_to_ticks(s.position_rad, cal));
  store(device.mem, mx1::kPresentSpeed, 2, units::present_speed_to_register(s.speed_rad_s, cal));
  store(device.mem, mx1::kPresentLoad, 2, units::load_to_register(s.load, cal));
  device.mem[mx1::kPresentVoltage] = units::voltage_to_register(s.voltage_v);
  device.mem[mx1::kPresentTemperature] = units::temperature_to_register(s.temperature_c);
  device.mem[mx1::kMoving] = std::abs(s.speed_rad_s) > 1e-3 ? 1 : 0;
  // Alarm shutdown: torque off while a shutdown-listed hardware error is active.
  const std::uint8_t hw = device_error(device) & (error_bits::kInputVoltage |
                                                  error_bits::kOverheating | error_bits::kOverload);
  if ((hw & device.mem[mx1::kAlarmShutdown]) != 0 && device.mem[mx1::kTorqueEnable] != 0) {
    device.mem[mx1::kTorqueEnable] = 0;
    push_command(device);
  }
}

std::uint8_t VirtualBus::status_error(Device& device, std::uint8_t error) {
  const std::uint8_t e = device_error(device) | error;
  device.command_error = 0;  // this status packet carries it
  return e;
}

std::size_t VirtualBus::encode_status(std::span<std::uint8_t> out, std::uint8_t id,
                                      std::uint8_t error, std::span<const std::uint8_t> params) {
  return v1::encode_status(out, id, error, params);
}

std::uint8_t VirtualBus::device_error(const Device& device) const {
  std::uint8_t e = device.command_error;
  if (device.servo_index >= 0) {
    const double volts = device.mem[mx1::kPresentVoltage];
    if (volts < device.mem[mx1::kMinVoltageLimit] || volts > device.mem[mx1::kMaxVoltageLimit]) {
      e |= error_bits::kInputVoltage;
    }
    if (device.mem[mx1::kPresentTemperature] > device.mem[mx1::kTemperatureLimit]) {
      e |= error_bits::kOverheating;
    }
    const int present_load = std::abs(units::signed_from_bit10(
        static_cast<std::uint16_t>(load(device.mem, mx1::kPresentLoad, 2))));
    const int limit = static_cast<int>(load(device.mem, mx1::kTorqueLimit, 2));
    // Overload: the load sits at the torque limit and the servo cannot move (stalled).
    const int speed = std::abs(units::signed_from_bit10(
        static_cast<std::uint16_t>(load(device.mem, mx1::kPresentSpeed, 2))));
    if (device.mem[mx1::kTorqueEnable] != 0 && limit > 0 && present_load >= limit && speed == 0) {
      e |= error_bits::kOverload;
    }
  }
  return e;
}

// A refused write sets its error bit on the device, for its next status packet.
std::uint8_t VirtualBus::write(Device& device, std::uint16_t address,
                               std::span<const std::uint8_t> data) {
  const std::size_t end = address + data.size();
  if (end > device.table->size) {
    device.command_error |= error_bits::kRange;
    return 0;
  }
  // Validate every register the write covers completely before changing anything.
  std::array<std::uint8_t, 256> next = device.mem;
  for (std::size_t k = 0; k < data.size(); ++k) next[address + k] = data[k];
  for (const Register& r : device.table->registers) {
    if (r.address < address || r.address + r.size > end) continue;
    if (r.access == Access::kRead) {
      store(next, r.address, r.size, load(device.mem, r.address, r.size));
      continue;
    }
    const std::uint32_t v = load(next, r.address, r.size);
    if (v < r.min || v > r.max) {
      device.command_error |= error_bits::kRange;
      return 0;
    }
  }
  if (device.servo_index >= 0 && address <= mx1::kGoalPosition + 1 && end > mx1::kGoalPosition) {
    const std::uint32_t goal = load(next, mx1::kGoalPosition, 2);
    const std::uint32_t cw = load(next, mx1::kCwAngleLimit, 2);
    const std::uint32_t ccw = load(next, mx1::kCcwAngleLimit, 2);
    if ((cw != 0 || ccw != 0) && (goal < cw || goal > ccw)) {
      device.command_error |= error_bits::kAngleLimit;
      store(next, mx1::kGoalPosition, 2, load(device.mem, mx1::kGoalPosition, 2));
    }
  }
  // Reserved bytes (no register) keep reading 0, as on the MX.
  for (std::size_t k = address; k < end; ++k) {
    if (device.table->covering(static_cast<std::uint16_t>(k)) == nullptr) next[k] = 0;
  }
  // Alarm shutdown: torque cannot be re-enabled while a shutdown error is active.
  const std::uint8_t hw = device_error(device) & (error_bits::kInputVoltage |
                                                  error_bits::kOverheating | error_bits::kOverload);
  if (device.servo_index >= 0 && (hw & next[mx1::kAlarmShutdown]) != 0)
    next[mx1::kTorqueEnable] = 0;
  device.mem = next;
  push_command(device);
  return 0;
}

bool VirtualBus::read_refused(Device& device, std::uint16_t address, std::uint16_t length,
                              std::uint8_t& error) {
  error = 0;
  if (address + length <= device.table->size) return false;
  device.command_error |= error_bits::kRange;
  return true;
}

bool VirtualBus::is_read_cycle(const Packet& packet) const {
  return packet.id == kBroadcastId && packet.instruction == instruction::kBulkRead;
}

void VirtualBus::on_bad_packet(Device& device, std::vector<std::uint8_t>& out,
                               std::int64_t& delay_us) {
  device.command_error |= error_bits::kChecksum;
  if (device.mem[mx1::kStatusReturnLevel] >= 2) reply(device, 0, {}, out, delay_us);
}

void VirtualBus::dispatch(const Packet& packet, std::vector<std::uint8_t>& out,
                          std::int64_t& delay_us) {
  const auto params = packet.parameters();
  if (packet.id != kBroadcastId) {
    handle_addressed(packet, params, out, delay_us);
  } else if (packet.instruction == instruction::kSyncWrite) {
    handle_sync_write(params);
  } else if (packet.instruction == instruction::kBulkRead) {
    handle_bulk_read(params, out, delay_us);
  } else {
    handle_broadcast(packet, params);
  }
}

void VirtualBus::handle_sync_write(std::span<const std::uint8_t> params) {
  ++counters_.sync_writes;
  if (params.size() < 2 || params[1] == 0) return;
  if ((params.size() - 2) % (params[1] + 1U) != 0) return;
  sync_write(params[0], params[1], params.subspan(2));
}

void VirtualBus::handle_bulk_read(std::span<const std::uint8_t> params,
                                  std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  // [0x00] then [length][id][address] per device.
  if (!params.empty() && (params.size() - 1) % 3 == 0) {
    std::array<ReadRequest, kMaxPacketBytes / 3> requests{};
    std::size_t n = 0;
    for (std::size_t k = 1; k + 3 <= params.size() && n < requests.size(); k += 3)
      requests[n++] = {.id = params[k + 1], .address = params[k + 2], .length = params[k]};
    read_chain(std::span(requests.data(), n), out, delay_us);
  }
  ++counters_.bulk_reads;  // after the replies: the faults count cycles by it (faults_active)
}

void VirtualBus::handle_broadcast(const Packet& packet, std::span<const std::uint8_t> params) {
  for (Device& d : devices_) {
    if (packet.instruction == instruction::kWrite && !params.empty()) {
      (void)write(d, params[0], params.subspan(1));
    } else if (packet.instruction == instruction::kAction && d.registered) {
      (void)action(d);
    } else if (packet.instruction == instruction::kRegWrite && !params.empty()) {
      register_write(d, params[0], params.subspan(1));
    } else if (packet.instruction == instruction::kReset) {
      reset_device(d);
    }
    d.command_error = 0;
    d.mem[mx1::kRegistered] = d.registered ? 1 : 0;
  }
}

void VirtualBus::handle_addressed(const Packet& packet, std::span<const std::uint8_t> params,
                                  std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  Device* d = find(packet.id);
  if (d == nullptr) return;
  refresh(*d);
  const std::uint8_t level = d->mem[mx1::kStatusReturnLevel];
  switch (packet.instruction) {
    case instruction::kPing:
      reply(*d, 0, {}, out, delay_us);
      return;
    case instruction::kRead: {
      if (params.size() != 2) {
        d->command_error |= error_bits::kInstruction;
        if (level >= 1) reply(*d, 0, {}, out, delay_us);
        return;
      }
      const std::size_t address = params[0];
      const std::size_t length = params[1];
      if (address + length > d->table->size) {
        d->command_error |= error_bits::kRange;
        if (level >= 1) reply(*d, 0, {}, out, delay_us);
        return;
      }
      if (level >= 1) {
        reply(*d, 0, std::span<const std::uint8_t>(d->mem.data() + address, length), out, delay_us);
      }
      return;
    }
    case instruction::kWrite:
      if (params.size() < 2) {
        d->command_error |= error_bits::kInstruction;
      } else {
        (void)write(*d, params[0], params.subspan(1));
      }
      break;
    case instruction::kRegWrite:
      if (params.size() < 2) {
        d->command_error |= error_bits::kInstruction;
      } else {
        register_write(*d, params[0], params.subspan(1));
      }
      break;
    case instruction::kAction:
      if (!d->registered) {
        d->command_error |= error_bits::kInstruction;
      } else {
        (void)action(*d);
      }
      break;
    case instruction::kReset:
      reset_device(*d);
      break;
    default:
      d->command_error |= error_bits::kInstruction;
      break;
  }
  if (level >= 2) {
    reply(*d, 0, {}, out, delay_us);
  } else {
    d->command_error = 0;
  }
}

}  // namespace stride::hal::dxl
