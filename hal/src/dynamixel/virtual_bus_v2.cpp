// Emulated MX(2.0) servos on a protocol 2.0 bus (see virtual_bus_v2.hpp).
#include "stride/hal/dynamixel/virtual_bus_v2.hpp"

#include <algorithm>
#include <cmath>

#include "stride/hal/dynamixel/codec_v2.hpp"

namespace stride::hal::dxl {

VirtualBusV2::VirtualBusV2(const Options& options, std::unique_ptr<VirtualBusPhysics> physics)
    : VirtualBusCore(options,
                     Layout{.protocol = Protocol::kV2,
                            .id = mx2::kId,
                            .return_delay = mx2::kReturnDelayTime,
                            .status_return_level = mx2::kStatusReturnLevel,
                            .registered = mx2::kRegisteredInstruction,
                            .unanswered_ends_chain = false},
                     std::move(physics)) {
  for (std::size_t i = 0; i < kServoCount; ++i) {
    Device s;
    s.id = static_cast<std::uint8_t>(i + 1);
    s.servo_index = static_cast<int>(i);
    s.table = calibration_[i].model == ServoModelId::kMx64 ? &mx64_v2_table() : &mx106_v2_table();
    s.mem[mx2::kId] = s.id;
    devices_.push_back(std::move(s));
  }
  for (Device& s : devices_) {
    reset(s, false);
    refresh(s);
  }
  start_clock();
}

void VirtualBusV2::reset(Device& servo, bool ram_only) {
  const std::uint8_t id = servo.mem[mx2::kId];
  for (const Register& r : servo.table->registers) {
    if (!ram_only || r.memory == Memory::kRam) store(servo.mem, r.address, r.size, r.initial);
  }
  servo.mem[mx2::kId] = id;
  const auto i = static_cast<std::size_t>(servo.servo_index);
  const double q = physics().servo_state(i).position_rad;
  store(servo.mem, mx2::kGoalPosition, 4, units::position_to_ticks(q, calibration_[i]));
  servo.registered = false;
  push_command(servo);
}

void VirtualBusV2::factory_reset(Device& servo, std::uint8_t option) {
  const std::uint8_t baud = servo.mem[mx2::kBaudRate];
  reset(servo, false);  // keeps the ID
  if (option == 0xFF) {
    const Register* id = servo.table->at(mx2::kId);
    servo.mem[mx2::kId] = static_cast<std::uint8_t>(id != nullptr ? id->initial : 1);
  }
  if (option == 0x02) servo.mem[mx2::kBaudRate] = baud;
}

std::uint32_t VirtualBusV2::peek(std::uint8_t id, std::uint16_t address, std::uint8_t size) const {
  const Device* s = find(id);
  return s != nullptr && address + size <= 256 ? load(s->mem, address, size) : 0;
}

void VirtualBusV2::push_command(Device& servo) {
  const ServoCalibration& cal = calibration_[static_cast<std::size_t>(servo.servo_index)];
  PhysicsServoCommand c;
  const auto ticks = static_cast<std::uint16_t>(
      std::min<std::uint32_t>(load(servo.mem, mx2::kGoalPosition, 4), 4095));
  c.goal_rad = units::ticks_to_position(ticks, cal);
  c.speed_limit_rad_s = units::v2_velocity_from_register(load(servo.mem, mx2::kProfileVelocity, 4));
  c.p_gain = static_cast<double>(load(servo.mem, mx2::kPositionPGain, 2)) / 16.0;
  c.torque_limit = 1.0;
  c.torque_enabled = servo.mem[mx2::kTorqueEnable] != 0;
  command(servo, c);
}

void VirtualBusV2::refresh(Device& servo) {
  const ServoCalibration& cal = calibration_[static_cast<std::size_t>(servo.servo_index)];
  const PhysicsServoState s = servo_state(servo);
  store(servo.mem, mx2::kPresentPosition, 4, units::position_to_ticks(s.position_rad, cal));
  const double velocity = cal.direction * s.speed_rad_s / units::kV2VelocityUnitRadS;
  store(servo.mem, mx2::kPresentVelocity, 4,
        static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(velocity))));
  store(servo.mem, 126, 2,
        static_cast<std::uint32_t>(
            static_cast<std::int16_t>(std::lround(cal.direction * s.load * 1000.0))));
  store(servo.mem, mx2::kPresentInputVoltage, 2, units::voltage_to_register(s.voltage_v));
  servo.mem[mx2::kPresentTemperature] = units::temperature_to_register(s.temperature_c);
  servo.mem[122] = std::abs(s.speed_rad_s) > 1e-3 ? 1 : 0;
  const bool hot = servo.mem[mx2::kPresentTemperature] > servo.mem[mx2::kTemperatureLimit];
  servo.mem[mx2::kHardwareErrorStatus] = hot ? 0x04 : 0x00;  // bit 2: overheating
  if (hot && (servo.mem[mx2::kShutdown] & 0x04) != 0 && servo.mem[mx2::kTorqueEnable] != 0) {
    servo.mem[mx2::kTorqueEnable] = 0;  // shutdown
    push_command(servo);
  }
}

std::uint8_t VirtualBusV2::write(Device& servo, std::uint16_t address,
                                 std::span<const std::uint8_t> data) {
  const std::size_t end = address + data.size();
  if (end > servo.table->size) return v2_error::kAccess;
  std::array<std::uint8_t, 256> next = servo.mem;
  for (std::size_t k = 0; k < data.size(); ++k) next[address + k] = data[k];
  const bool torque_on = servo.mem[mx2::kTorqueEnable] != 0;
  for (const Register& r : servo.table->registers) {
    if (r.address + r.size <= address || r.address >= end) continue;  // not touched
    if (r.access == Access::kRead) return v2_error::kAccess;
    if (r.memory == Memory::kEeprom && torque_on) return v2_error::kAccess;
    if (r.address < address || r.address + r.size > end) return v2_error::kDataLength;
    const std::uint32_t v = load(next, r.address, r.size);
    if (v < r.min || v > r.max) return v2_error::kDataRange;
  }
  // Position control mode: Goal Position must lie within [Min, Max Position Limit].
  if (address < mx2::kGoalPosition + 4 && end > mx2::kGoalPosition &&
      next[mx2::kOperatingMode] == mx2::kPositionControlMode) {
    const std::uint32_t goal = load(next, mx2::kGoalPosition, 4);
    if (goal < load(next, mx2::kMinPositionLimit, 4) ||
        goal > load(next, mx2::kMaxPositionLimit, 4))
      return v2_error::kDataLimit;
  }
  if ((servo.mem[mx2::kHardwareErrorStatus] & servo.mem[mx2::kShutdown]) != 0)
    next[mx2::kTorqueEnable] = 0;
  servo.mem = next;
  push_command(servo);
  return 0;
}

std::uint8_t VirtualBusV2::status_id(const Device& device) const {
  return device.mem[mx2::kId];
}

std::uint8_t VirtualBusV2::status_error(Device& device, std::uint8_t error) {
  if (device.mem[mx2::kHardwareErrorStatus] != 0) error |= v2_error::kAlert;
  return error;
}

std::size_t VirtualBusV2::encode_status(std::span<std::uint8_t> out, std::uint8_t id,
                                        std::uint8_t error, std::span<const std::uint8_t> params) {
  return v2::encode_status(out, id, error, params);
}

bool VirtualBusV2::read_refused(Device& device, std::uint16_t address, std::uint16_t length,
                                std::uint8_t& error) {
  if (address + length <= device.table->size && length != 0) return false;
  error = v2_error::kAccess;
  return true;
}

bool VirtualBusV2::is_read_cycle(const Packet& packet) const {
  return packet.instruction == instruction::kSyncRead ||
         packet.instruction == instruction::kBulkRead;
}

void VirtualBusV2::on_bad_packet(Device& device, std::vector<std::uint8_t>& out,
                                 std::int64_t& delay_us) {
  if (device.mem[mx2::kStatusReturnLevel] >= 2)
    (void)reply(device, v2_error::kCrc, {}, out, delay_us);
}

void VirtualBusV2::handle_sync(std::uint8_t code, std::span<const std::uint8_t> p,
                               std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  if (p.size() < 4) return;
  const std::uint16_t address = read_u16(p.data());
  const std::uint16_t length = read_u16(p.data() + 2);
  if (code == instruction::kSyncRead) {
    std::array<ReadRequest, kMaxPacketBytes> requests{};
    std::size_t n = 0;
    for (std::size_t k = 4; k < p.size() && n < requests.size(); ++k)
      requests[n++] = {.id = p[k], .address = address, .length = length};
    read_chain(std::span(requests.data(), n), out, delay_us);
    ++counters_.sync_reads;
    return;
  }
  ++counters_.sync_writes;
  if (length != 0) sync_write(address, length, p.subspan(4));
}

void VirtualBusV2::handle_bulk_read(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out,
                                    std::int64_t& delay_us) {
  // [id][address, 2 bytes][length, 2 bytes] per servo.
  std::array<ReadRequest, kMaxPacketBytes / 5> requests{};
  std::size_t n = 0;
  for (std::size_t k = 0; k + 5 <= p.size() && n < requests.size(); k += 5) {
    requests[n++] = {
        .id = p[k], .address = read_u16(p.data() + k + 1), .length = read_u16(p.data() + k + 3)};
  }
  read_chain(std::span(requests.data(), n), out, delay_us);
  ++counters_.bulk_reads;
}

void VirtualBusV2::dispatch(const Packet& packet, std::vector<std::uint8_t>& out,
                            std::int64_t& delay_us) {
  const auto p = packet.parameters();
  const bool broadcast = packet.id == kBroadcastId;
  const std::uint8_t code = packet.instruction;
  if (code == instruction::kPing) {
    for (Device& s : devices_) {
      if (!broadcast && s.mem[mx2::kId] != packet.id) continue;
      const std::array<std::uint8_t, 3> info{s.mem[0], s.mem[1], s.mem[6]};
      (void)reply(s, 0, info, out, delay_us);
    }
    return;
  }
  if (code == instruction::kSyncRead || code == instruction::kSyncWrite) {
    if (broadcast) handle_sync(code, p, out, delay_us);
    return;
  }
  if (code == instruction::kBulkRead) {
    if (broadcast) handle_bulk_read(p, out, delay_us);
    return;
  }
  handle_each(packet, p, out, delay_us);
}

void VirtualBusV2::handle_each(const Packet& packet, std::span<const std::uint8_t> p,
                               std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  const bool broadcast = packet.id == kBroadcastId;
  const std::uint8_t code = packet.instruction;
  for (Device& s : devices_) {
    if (!broadcast && s.mem[mx2::kId] != packet.id) continue;
    std::uint8_t error = 0;
    bool is_read = false;
    std::uint8_t reset_option = 0;  // FACTORY_RESET to do once the status packet is out
    switch (code) {
      case instruction::kRead:
        if (p.size() != 4) {
          error = v2_error::kDataLength;
          break;
        }
        if (!broadcast)
          (void)read_reply(s, read_u16(p.data()), read_u16(p.data() + 2), out, delay_us);
        is_read = true;
        break;
      case instruction::kWrite:
        error = p.size() < 3 ? v2_error::kDataLength : write(s, read_u16(p.data()), p.subspan(2));
        break;
      case instruction::kRegWrite:
        if (p.size() < 3) {
          error = v2_error::kDataLength;
        } else {
          register_write(s, read_u16(p.data()), p.subspan(2));
        }
        break;
      case instruction::kAction:
        if (!s.registered) {
          error = v2_error::kInstruction;
        } else {
          error = action(s);
        }
        break;
      case instruction::kReboot:
        reset(s, true);
        break;
      case instruction::kReset:
        if (p.size() != 1) {
          error = v2_error::kDataLength;
        } else if (p[0] != 0xFF && p[0] != 0x01 && p[0] != 0x02) {
          error = v2_error::kDataRange;
        } else if (!(broadcast && p[0] == 0xFF)) {  // e-manual: not executed on broadcast
          reset_option = p[0];
        }
        break;
      default:
        error = v2_error::kInstruction;
        break;
    }
    if (!broadcast && !is_read && s.mem[mx2::kStatusReturnLevel] >= 2)
      (void)reply(s, error, {}, out, delay_us);
    if (reset_option != 0) factory_reset(s, reset_option);
  }
}

}  // namespace stride::hal::dxl
