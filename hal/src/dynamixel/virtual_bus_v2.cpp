// Emulated MX(2.0) servos on a protocol 2.0 bus (see virtual_bus_v2.hpp).
#include "stride/hal/dynamixel/virtual_bus_v2.hpp"

#include <algorithm>
#include <cmath>

#include "stride/hal/dynamixel/byte_stream.hpp"
#include "stride/hal/dynamixel/codec_v2.hpp"

namespace stride::hal::dxl {

namespace {

std::uint32_t get(const std::array<std::uint8_t, 256>& mem, std::uint16_t address,
                  std::uint8_t size) {
  std::uint32_t v = 0;
  for (std::uint8_t i = 0; i < size; ++i)
    v |= static_cast<std::uint32_t>(mem[address + i]) << (8 * i);
  return v;
}

void put(std::array<std::uint8_t, 256>& mem, std::uint16_t address, std::uint8_t size,
         std::uint32_t v) {
  for (std::uint8_t i = 0; i < size; ++i)
    mem[address + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

}  // namespace

VirtualBusV2::VirtualBusV2(const Options& options, std::unique_ptr<VirtualBusPhysics> physics)
    : options_(options), physics_(std::move(physics)), rng_(options.faults.seed) {
  for (std::size_t i = 0; i < kServoCount; ++i) {
    Servo s;
    s.index = i;
    s.table =
        options_.calibration[i].model == ServoModelId::kMx64 ? &mx64_v2_table() : &mx106_v2_table();
    s.mem[mx2::kId] = static_cast<std::uint8_t>(i + 1);
    servos_.push_back(std::move(s));
  }
  for (Servo& s : servos_) {
    reset(s, false);
    refresh(s);
  }
  last_advance_ns_ = monotonic_ns();
}

void VirtualBusV2::reset(Servo& servo, bool ram_only) {
  const std::uint8_t id = servo.mem[mx2::kId];
  for (const Register& r : servo.table->registers) {
    if (!ram_only || r.memory == Memory::kRam) put(servo.mem, r.address, r.size, r.initial);
  }
  servo.mem[mx2::kId] = id;
  const double q = physics_->servo_state(servo.index).position_rad;
  put(servo.mem, mx2::kGoalPosition, 4,
      units::position_to_ticks(q, options_.calibration[servo.index]));
  servo.registered = false;
  push_command(servo);
}

void VirtualBusV2::factory_reset(Servo& servo, std::uint8_t option) {
  const std::uint8_t baud = servo.mem[mx2::kBaudRate];
  reset(servo, false);  // keeps the ID
  if (option == 0xFF) {
    const Register* id = servo.table->at(mx2::kId);
    servo.mem[mx2::kId] = static_cast<std::uint8_t>(id != nullptr ? id->initial : 1);
  }
  if (option == 0x02) servo.mem[mx2::kBaudRate] = baud;
}

bool VirtualBusV2::faults_active() const {
  return counters_.bulk_reads + counters_.sync_reads >= options_.faults.start_after_cycles;
}

VirtualBusV2::Servo* VirtualBusV2::find(std::uint8_t id) {
  for (Servo& s : servos_) {
    if (s.mem[mx2::kId] == id) return &s;
  }
  return nullptr;
}

std::uint32_t VirtualBusV2::peek(std::uint8_t id, std::uint16_t address, std::uint8_t size) const {
  for (const Servo& s : servos_) {
    if (s.mem[mx2::kId] == id && address + size <= 256) return get(s.mem, address, size);
  }
  return 0;
}

void VirtualBusV2::push_command(Servo& servo) {
  const ServoCalibration& cal = options_.calibration[servo.index];
  PhysicsServoCommand c;
  const auto ticks = static_cast<std::uint16_t>(
      std::min<std::uint32_t>(get(servo.mem, mx2::kGoalPosition, 4), 4095));
  c.goal_rad = units::ticks_to_position(ticks, cal);
  const double q = physics_->servo_state(servo.index).position_rad;
  while (c.goal_rad - q > units::kPi) c.goal_rad -= 2.0 * units::kPi;
  while (c.goal_rad - q < -units::kPi) c.goal_rad += 2.0 * units::kPi;
  c.speed_limit_rad_s = units::v2_velocity_from_register(get(servo.mem, mx2::kProfileVelocity, 4));
  c.p_gain = static_cast<double>(get(servo.mem, mx2::kPositionPGain, 2)) / 16.0;
  c.torque_limit = 1.0;
  c.torque_enabled = servo.mem[mx2::kTorqueEnable] != 0;
  physics_->set_command(servo.index, c);
}

void VirtualBusV2::refresh(Servo& servo) {
  const ServoCalibration& cal = options_.calibration[servo.index];
  PhysicsServoState s = physics_->servo_state(servo.index);
  if (options_.faults.overheat[servo.mem[mx2::kId]] && faults_active()) s.temperature_c = 85.0;
  put(servo.mem, mx2::kPresentPosition, 4, units::position_to_ticks(s.position_rad, cal));
  const double velocity = cal.direction * s.speed_rad_s / units::kV2VelocityUnitRadS;
  put(servo.mem, mx2::kPresentVelocity, 4,
      static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(velocity))));
  put(servo.mem, 126, 2,
      static_cast<std::uint32_t>(
          static_cast<std::int16_t>(std::lround(cal.direction * s.load * 1000.0))));
  put(servo.mem, mx2::kPresentInputVoltage, 2, units::voltage_to_register(s.voltage_v));
  servo.mem[mx2::kPresentTemperature] = units::temperature_to_register(s.temperature_c);
  servo.mem[122] = std::abs(s.speed_rad_s) > 1e-3 ? 1 : 0;
  const bool hot = servo.mem[mx2::kPresentTemperature] > servo.mem[mx2::kTemperatureLimit];
  servo.mem[mx2::kHardwareErrorStatus] = hot ? 0x04 : 0x00;  // bit 2: overheating
  if (hot && (servo.mem[mx2::kShutdown] & 0x04) != 0 && servo.mem[mx2::kTorqueEnable] != 0) {
    servo.mem[mx2::kTorqueEnable] = 0;  // shutdown
    push_command(servo);
  }
}

std::uint8_t VirtualBusV2::write(Servo& servo, std::uint16_t address,
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
    const std::uint32_t v = get(next, r.address, r.size);
    if (v < r.min || v > r.max) return v2_error::kDataRange;
  }
  // Position control mode: Goal Position must lie within [Min, Max Position Limit].
  if (address < mx2::kGoalPosition + 4 && end > mx2::kGoalPosition &&
      next[mx2::kOperatingMode] == mx2::kPositionControlMode) {
    const std::uint32_t goal = get(next, mx2::kGoalPosition, 4);
    if (goal < get(next, mx2::kMinPositionLimit, 4) || goal > get(next, mx2::kMaxPositionLimit, 4))
      return v2_error::kDataLimit;
  }
  if ((servo.mem[mx2::kHardwareErrorStatus] & servo.mem[mx2::kShutdown]) != 0)
    next[mx2::kTorqueEnable] = 0;
  servo.mem = next;
  push_command(servo);
  return 0;
}

bool VirtualBusV2::reply(Servo& servo, std::uint8_t error, std::span<const std::uint8_t> params,
                         std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  if (options_.faults.silent[servo.mem[mx2::kId]] && faults_active()) {
    ++counters_.silenced;
    return false;
  }
  if (servo.mem[mx2::kHardwareErrorStatus] != 0) error |= v2_error::kAlert;
  std::array<std::uint8_t, kMaxPacketBytes> packet{};
  const std::size_t n = v2::encode_status(packet, servo.mem[mx2::kId], error, params);
  if (n == 0) return false;
  if (faults_active() && !inject_reply_faults(options_.faults, rng_, {packet.data(), n}, counters_))
    return true;  // the servo answered; the host never hears it (the chain goes on)
  delay_us += 2 * static_cast<std::int64_t>(servo.mem[mx2::kReturnDelayTime]);
  out.insert(out.end(), packet.begin(), packet.begin() + static_cast<std::ptrdiff_t>(n));
  ++counters_.replies;
  if (error != 0) ++counters_.error_replies;
  return true;
}

bool VirtualBusV2::read_reply(Servo& servo, std::uint16_t address, std::uint16_t length,
                              std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  if (servo.mem[mx2::kStatusReturnLevel] < 1) return true;
  refresh(servo);
  if (address + length > servo.table->size || length == 0) {
    return reply(servo, v2_error::kAccess, {}, out, delay_us);
  }
  return reply(servo, 0, std::span<const std::uint8_t>(servo.mem.data() + address, length), out,
               delay_us);
}

void VirtualBusV2::advance_time(bool cycle) {
  const std::int64_t now = monotonic_ns();
  if (options_.lockstep) {
    if (cycle) physics_->advance(static_cast<double>(options_.period_ns) * 1e-9);
    last_advance_ns_ = now;
    return;
  }
  double dt = std::min(static_cast<double>(now - last_advance_ns_) * 1e-9, 2.0);
  last_advance_ns_ = now;
  while (dt > 1e-9) {
    const double step = std::min(dt, 0.005);
    physics_->advance(step);
    dt -= step;
  }
}

void VirtualBusV2::receive(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out,
                           std::int64_t& reply_delay_us) {
  Packet packet;
  std::size_t offset = 0;
  while (offset < bytes.size()) {
    offset += parser_.feed(bytes.subspan(offset));
    while (parser_.next(packet)) handle(packet, out, reply_delay_us);
    while (seen_bad_ < parser_.stats().bad_checksum) {
      ++seen_bad_;
      ++counters_.bad_packets;
      Servo* s = find(parser_.last_bad_id());
      if (s != nullptr && s->mem[mx2::kStatusReturnLevel] >= 2) {
        (void)reply(*s, v2_error::kCrc, {}, out, reply_delay_us);
      }
    }
  }
}

void VirtualBusV2::handle_sync(std::uint8_t code, std::span<const std::uint8_t> p,
                               std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  if (p.size() < 4) return;
  const std::uint16_t address = read_u16(p.data());
  const std::uint16_t length = read_u16(p.data() + 2);
  if (code == instruction::kSyncRead) {
    // Replies in list order, each servo after its predecessor's status packet.
    for (std::size_t k = 4; k < p.size(); ++k) {
      Servo* s = find(p[k]);
      if (s != nullptr && !read_reply(*s, address, length, out, delay_us)) break;
    }
    ++counters_.sync_reads;
    return;
  }
  ++counters_.sync_writes;
  if (length == 0) return;
  for (std::size_t k = 4; k + 1 + length <= p.size(); k += 1U + length) {
    if (Servo* s = find(p[k])) (void)write(*s, address, p.subspan(k + 1, length));
  }
}

void VirtualBusV2::handle_bulk_read(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out,
                                    std::int64_t& delay_us) {
  for (std::size_t k = 0; k + 5 <= p.size(); k += 5) {
    Servo* s = find(p[k]);
    if (s != nullptr &&
        !read_reply(*s, read_u16(p.data() + k + 1), read_u16(p.data() + k + 3), out, delay_us))
      break;
  }
  ++counters_.bulk_reads;
}

void VirtualBusV2::handle(const Packet& packet, std::vector<std::uint8_t>& out,
                          std::int64_t& delay_us) {
  if (packet.is_status) return;
  ++counters_.instructions;
  const auto p = packet.parameters();
  const bool broadcast = packet.id == kBroadcastId;
  const std::uint8_t code = packet.instruction;
  advance_time(code == instruction::kSyncRead || code == instruction::kBulkRead);

  if (code == instruction::kPing) {
    for (Servo& s : servos_) {
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
  for (Servo& s : servos_) {
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
          s.registered = true;
          s.reg_address = read_u16(p.data());
          s.reg_data.assign(p.begin() + 2, p.end());
          s.mem[mx2::kRegisteredInstruction] = 1;
        }
        break;
      case instruction::kAction:
        if (!s.registered) {
          error = v2_error::kInstruction;
        } else {
          error = write(s, s.reg_address, s.reg_data);
          s.registered = false;
          s.mem[mx2::kRegisteredInstruction] = 0;
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
