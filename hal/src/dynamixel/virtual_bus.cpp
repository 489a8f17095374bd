// Emulated Dynamixel 1.0 bus: MX servos and the CM730 (see virtual_bus.hpp).
#include "stride/hal/dynamixel/virtual_bus.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "stride/hal/dynamixel/byte_stream.hpp"
#include "stride/hal/dynamixel/codec_v1.hpp"

namespace stride::hal::dxl {

namespace {

std::uint32_t load_value(const std::array<std::uint8_t, 256>& mem, std::uint16_t address,
                         std::uint8_t size) {
  std::uint32_t v = 0;
  for (std::uint8_t i = 0; i < size; ++i)
    v |= static_cast<std::uint32_t>(mem[address + i]) << (8 * i);
  return v;
}

void store_value(std::array<std::uint8_t, 256>& mem, std::uint16_t address, std::uint8_t size,
                 std::uint32_t v) {
  for (std::uint8_t i = 0; i < size; ++i)
    mem[address + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

}  // namespace

VirtualBus::VirtualBus(const Options& options, std::unique_ptr<VirtualBusPhysics> physics)
    : options_(options), physics_(std::move(physics)), rng_(options.faults.seed) {
  for (std::size_t i = 0; i < kServoCount; ++i) {
    Device d;
    d.id = static_cast<std::uint8_t>(i + 1);
    d.servo_index = static_cast<int>(i);
    d.table =
        options_.calibration[i].model == ServoModelId::kMx64 ? &mx64_v1_table() : &mx106_v1_table();
    devices_.push_back(std::move(d));
  }
  Device cm;
  cm.id = kCm730Id;
  cm.table = &cm730_table(options_.cm730_profile);
  devices_.push_back(std::move(cm));
  for (Device& d : devices_) {
    reset_device(d);
    refresh(d);
  }
  last_advance_ns_ = monotonic_ns();
}

void VirtualBus::reset_device(Device& device) {
  const std::uint8_t id = device.id;
  device.mem.fill(0);
  for (const Register& r : device.table->registers)
    store_value(device.mem, r.address, r.size, r.initial);
  device.mem[mx1::kId] = id;  // RESET keeps the ID here so the emulated bus stays addressable
  if (device.servo_index >= 0) {
    const std::size_t i = static_cast<std::size_t>(device.servo_index);
    const auto ticks =
        units::position_to_ticks(physics_->servo_state(i).position_rad, options_.calibration[i]);
    store_value(device.mem, mx1::kGoalPosition, 2, ticks);
    push_command(device);
  }
  device.registered = false;
}

VirtualBus::Device* VirtualBus::find(std::uint8_t id) {
  for (Device& d : devices_) {
    if (d.mem[mx1::kId] == id) return &d;
  }
  return nullptr;
}

std::uint8_t VirtualBus::peek(std::uint8_t id, std::uint8_t address) const {
  for (const Device& d : devices_) {
    if (d.mem[mx1::kId] == id) return d.mem[address];
  }
  return 0;
}

bool VirtualBus::faults_active() const {
  return counters_.bulk_reads >= options_.faults.start_after_cycles;
}

void VirtualBus::push_command(Device& device) {
  if (device.servo_index < 0) return;
  const std::size_t i = static_cast<std::size_t>(device.servo_index);
  const ServoCalibration& cal = options_.calibration[i];
  PhysicsServoCommand c;
  c.goal_rad = units::ticks_to_position(
      static_cast<std::uint16_t>(load_value(device.mem, mx1::kGoalPosition, 2)), cal);
  // ticks_to_position wraps into [-pi, pi); keep the goal on the side nearest the joint.
  const double q = physics_->servo_state(i).position_rad;
  while (c.goal_rad - q > units::kPi) c.goal_rad -= 2.0 * units::kPi;
  while (c.goal_rad - q < -units::kPi) c.goal_rad += 2.0 * units::kPi;
  c.speed_limit_rad_s = units::moving_speed_from_register(
      static_cast<std::uint16_t>(load_value(device.mem, mx1::kMovingSpeed, 2)));
  c.p_gain = device.mem[mx1::kPGain];
  c.torque_limit = units::torque_limit_from_register(
      static_cast<std::uint16_t>(load_value(device.mem, mx1::kTorqueLimit, 2)));
  c.torque_enabled = device.mem[mx1::kTorqueEnable] != 0;
  physics_->set_command(i, c);
}

// Present values from the physics; hardware error bits; alarm shutdown.
void VirtualBus::refresh(Device& device) {
  if (device.servo_index < 0) {
    const PhysicsImu imu = physics_->imu();
    if (options_.cm730_profile == Cm730Profile::kNimbro) {
      namespace n = cm730_nimbro;
      for (std::size_t k = 0; k < 3; ++k) {
        const auto offset = static_cast<std::uint16_t>(2 * k);
        store_value(device.mem, n::kGyroX + offset, 2,
                    units::nimbro_gyro_to_raw(imu.gyro_rad_s[k]));
        store_value(device.mem, n::kAccelX + offset, 2,
                    units::nimbro_accel_to_raw(imu.accel_mps2[k]));
        store_value(device.mem, n::kMagX + offset, 2, units::nimbro_mag_to_raw(imu.mag_gauss[k]));
      }
      device.mem[n::kBatteryVoltage] = units::voltage_to_register(15.0);
      return;
    }
    store_value(device.mem, cm730::kAccelX, 2, units::accel_to_raw(imu.accel_mps2[0]));
    store_value(device.mem, cm730::kAccelY, 2, units::accel_to_raw(imu.accel_mps2[1]));
    store_value(device.mem, cm730::kAccelZ, 2, units::accel_to_raw(imu.accel_mps2[2]));
    store_value(device.mem, cm730::kGyroX, 2, units::gyro_to_raw(imu.gyro_rad_s[0]));
    store_value(device.mem, cm730::kGyroY, 2, units::gyro_to_raw(imu.gyro_rad_s[1]));
    store_value(device.mem, cm730::kGyroZ, 2, units::gyro_to_raw(imu.gyro_rad_s[2]));
    device.mem[cm730::kVoltage] = units::voltage_to_register(15.0);
    return;
  }
  const std::size_t i = static_cast<std::size_t>(device.servo_index);
  const ServoCalibration& cal = options_.calibration[i];
  PhysicsServoState s = physics_->servo_state(i);
  if (options_.faults.overheat[device.id] && faults_active()) s.temperature_c = 85.0;
  store_value(device.mem, mx1::kPresentPosition, 2, units::position_to_ticks(s.position_rad, cal));
  store_value(device.mem, mx1::kPresentSpeed, 2,
              units::present_speed_to_register(s.speed_rad_s, cal));
  store_value(device.mem, mx1::kPresentLoad, 2, units::load_to_register(s.load, cal));
  device.mem[mx1::kPresentVoltage] = units::voltage_to_register(s.voltage_v);
  device.mem[mx1::kPresentTemperature] = units::temperature_to_register(s.temperature_c);
  device.mem[mx1::kMoving] = std::abs(s.speed_rad_s) > 1e-3 ? 1 : 0;
  // Alarm shutdown: torque off while a shutdown-listed hardware error is active.
  const std::uint8_t hw = status_error(device) & (error_bits::kInputVoltage |
                                                  error_bits::kOverheating | error_bits::kOverload);
  if ((hw & device.mem[mx1::kAlarmShutdown]) != 0 && device.mem[mx1::kTorqueEnable] != 0) {
    device.mem[mx1::kTorqueEnable] = 0;
    push_command(device);
  }
}

std::uint8_t VirtualBus::status_error(Device& device) {
  std::uint8_t e = device.command_error;
  if (device.servo_index >= 0) {
    const double volts = device.mem[mx1::kPresentVoltage];
    if (volts < device.mem[mx1::kMinVoltageLimit] || volts > device.mem[mx1::kMaxVoltageLimit]) {
      e |= error_bits::kInputVoltage;
    }
    if (device.mem[mx1::kPresentTemperature] > device.mem[mx1::kTemperatureLimit]) {
      e |= error_bits::kOverheating;
    }
    const int load = std::abs(units::signed_from_bit10(
        static_cast<std::uint16_t>(load_value(device.mem, mx1::kPresentLoad, 2))));
    const int limit = static_cast<int>(load_value(device.mem, mx1::kTorqueLimit, 2));
    // Overload: the load sits at the torque limit and the servo cannot move (stalled).
    const int speed = std::abs(units::signed_from_bit10(
        static_cast<std::uint16_t>(load_value(device.mem, mx1::kPresentSpeed, 2))));
    if (device.mem[mx1::kTorqueEnable] != 0 && limit > 0 && load >= limit && speed == 0) {
      e |= error_bits::kOverload;
    }
  }
  return e;
}

bool VirtualBus::apply_write(Device& device, std::uint8_t address,
                             std::span<const std::uint8_t> data) {
  const std::size_t end = address + data.size();
  if (end > device.table->size) {
    device.command_error |= error_bits::kRange;
    return false;
  }
  // Validate every register the write covers completely before changing anything.
  std::array<std::uint8_t, 256> next = device.mem;
  for (std::size_t k = 0; k < data.size(); ++k) next[address + k] = data[k];
  for (const Register& r : device.table->registers) {
    if (r.address < address || r.address + r.size > end) continue;
    if (r.access == Access::kRead) {
      store_value(next, r.address, r.size, load_value(device.mem, r.address, r.size));
      continue;
    }
    const std::uint32_t v = load_value(next, r.address, r.size);
    if (v < r.min || v > r.max) {
      device.command_error |= error_bits::kRange;
      return false;
    }
  }
  if (device.servo_index >= 0 && address <= mx1::kGoalPosition + 1 && end > mx1::kGoalPosition) {
    const std::uint32_t goal = load_value(next, mx1::kGoalPosition, 2);
    const std::uint32_t cw = load_value(next, mx1::kCwAngleLimit, 2);
    const std::uint32_t ccw = load_value(next, mx1::kCcwAngleLimit, 2);
    if ((cw != 0 || ccw != 0) && (goal < cw || goal > ccw)) {
      device.command_error |= error_bits::kAngleLimit;
      store_value(next, mx1::kGoalPosition, 2, load_value(device.mem, mx1::kGoalPosition, 2));
    }
  }
  // Reserved bytes (no register) keep reading 0, as on the MX.
  for (std::size_t k = address; k < end; ++k) {
    if (device.table->covering(static_cast<std::uint16_t>(k)) == nullptr) next[k] = 0;
  }
  // Alarm shutdown: torque cannot be re-enabled while a shutdown error is active.
  const std::uint8_t hw = status_error(device) & (error_bits::kInputVoltage |
                                                  error_bits::kOverheating | error_bits::kOverload);
  if (device.servo_index >= 0 && (hw & next[mx1::kAlarmShutdown]) != 0)
    next[mx1::kTorqueEnable] = 0;
  device.mem = next;
  push_command(device);
  return true;
}

bool VirtualBus::reply(Device& device, std::span<const std::uint8_t> params,
                       std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  if (options_.faults.silent[device.id] && faults_active()) {
    ++counters_.silenced;
    return false;
  }
  std::array<std::uint8_t, 260> packet{};
  const std::uint8_t error = status_error(device);
  const std::size_t n = v1::encode_status(packet, device.id, error, params);
  device.command_error = 0;
  if (n == 0) return false;
  if (faults_active() && !inject_reply_faults(options_.faults, rng_, {packet.data(), n}, counters_))
    return true;  // the device answered; the host never hears it (the chain goes on)
  delay_us += 2 * static_cast<std::int64_t>(device.mem[mx1::kReturnDelayTime]);
  out.insert(out.end(), packet.begin(), packet.begin() + static_cast<std::ptrdiff_t>(n));
  ++counters_.replies;
  if (error != 0) ++counters_.error_replies;
  return true;
}

void VirtualBus::advance_time() {
  const std::int64_t now = monotonic_ns();
  if (options_.lockstep) {
    last_advance_ns_ = now;
    return;
  }
  double dt = static_cast<double>(now - last_advance_ns_) * 1e-9;
  last_advance_ns_ = now;
  dt = std::min(dt, 2.0);  // after a long idle gap, do not integrate minutes at once
  while (dt > 1e-9) {
    const double step = std::min(dt, 0.005);
    physics_->advance(step);
    dt -= step;
  }
}

void VirtualBus::receive(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out,
                         std::int64_t& reply_delay_us) {
  Packet packet;
  std::size_t offset = 0;
  while (offset < bytes.size()) {
    offset += parser_.feed(bytes.subspan(offset));
    while (parser_.next(packet)) handle(packet, out, reply_delay_us);
    // A damaged packet addressed to a device is answered with the checksum error bit.
    while (seen_bad_checksum_ < parser_.stats().bad_checksum) {
      ++seen_bad_checksum_;
      ++counters_.bad_packets;
      Device* d = find(parser_.last_bad_id());
      if (d != nullptr && parser_.last_bad_id() != kBroadcastId) {
        d->command_error |= error_bits::kChecksum;
        if (d->mem[mx1::kStatusReturnLevel] >= 2) reply(*d, {}, out, reply_delay_us);
      }
    }
  }
}

void VirtualBus::handle(const Packet& packet, std::vector<std::uint8_t>& out,
                        std::int64_t& delay_us) {
  ++counters_.instructions;
  advance_time();
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
  const std::size_t record = params[1] + 1U;
  if ((params.size() - 2) % record != 0) return;
  for (std::size_t k = 2; k + record <= params.size(); k += record) {
    Device* d = find(params[k]);
    if (d != nullptr) {
      (void)apply_write(*d, params[0], params.subspan(k + 1, params[1]));
      d->command_error = 0;  // no status packet carries it
    }
  }
}

void VirtualBus::handle_bulk_read(std::span<const std::uint8_t> params,
                                  std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  if (options_.lockstep) physics_->advance(static_cast<double>(options_.period_ns) * 1e-9);
  if (params.empty() || (params.size() - 1) % 3 != 0) {
    ++counters_.bulk_reads;
    return;
  }
  for (std::size_t k = 1; k + 3 <= params.size(); k += 3) {
    Device* d = find(params[k + 1]);
    if (d == nullptr || d->mem[mx1::kStatusReturnLevel] == 0) break;  // the chain stops here
    refresh(*d);
    const std::size_t address = params[k + 2];
    const std::size_t length = params[k];
    bool sent = false;
    if (address + length > d->table->size) {
      d->command_error |= error_bits::kRange;
      sent = reply(*d, {}, out, delay_us);
    } else {
      sent =
          reply(*d, std::span<const std::uint8_t>(d->mem.data() + address, length), out, delay_us);
    }
    if (!sent) break;  // the next device waits for this one's status packet forever
  }
  ++counters_.bulk_reads;  // after the replies: the faults count cycles by it (faults_active)
}

void VirtualBus::handle_broadcast(const Packet& packet, std::span<const std::uint8_t> params) {
  for (Device& d : devices_) {
    if (packet.instruction == instruction::kWrite && !params.empty()) {
      (void)apply_write(d, params[0], params.subspan(1));
    } else if (packet.instruction == instruction::kAction && d.registered) {
      (void)apply_write(d, d.reg_address, d.reg_data);
      d.registered = false;
    } else if (packet.instruction == instruction::kRegWrite && !params.empty()) {
      d.registered = true;
      d.reg_address = params[0];
      d.reg_data.assign(params.begin() + 1, params.end());
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
      reply(*d, {}, out, delay_us);
      return;
    case instruction::kRead: {
      if (params.size() != 2) {
        d->command_error |= error_bits::kInstruction;
        if (level >= 1) reply(*d, {}, out, delay_us);
        return;
      }
      const std::size_t address = params[0];
      const std::size_t length = params[1];
      if (address + length > d->table->size) {
        d->command_error |= error_bits::kRange;
        if (level >= 1) reply(*d, {}, out, delay_us);
        return;
      }
      if (level >= 1) {
        reply(*d, std::span<const std::uint8_t>(d->mem.data() + address, length), out, delay_us);
      }
      return;
    }
    case instruction::kWrite:
      if (params.size() < 2) {
        d->command_error |= error_bits::kInstruction;
      } else {
        (void)apply_write(*d, params[0], params.subspan(1));
      }
      break;
    case instruction::kRegWrite:
      if (params.size() < 2) {
        d->command_error |= error_bits::kInstruction;
      } else {
        d->registered = true;
        d->reg_address = params[0];
        d->reg_data.assign(params.begin() + 1, params.end());
        d->mem[mx1::kRegistered] = 1;
      }
      break;
    case instruction::kAction:
      if (!d->registered) {
        d->command_error |= error_bits::kInstruction;
      } else {
        (void)apply_write(*d, d->reg_address, d->reg_data);
        d->registered = false;
        d->mem[mx1::kRegistered] = 0;
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
    reply(*d, {}, out, delay_us);
  } else {
    d->command_error = 0;
  }
}

}  // namespace stride::hal::dxl
