// The shared body of the emulated Dynamixel buses (see virtual_bus_core.hpp).
#include "stride/hal/dynamixel/virtual_bus_core.hpp"

#include <algorithm>

#include "stride/hal/dynamixel/byte_stream.hpp"

namespace stride::hal::dxl {

VirtualBusCore::VirtualBusCore(const Options& common, const Layout& layout,
                               std::unique_ptr<VirtualBusPhysics> physics)
    : calibration_(common.calibration),
      lockstep_(common.lockstep),
      period_ns_(common.period_ns),
      faults_(common.faults),
      layout_(layout),
      physics_(std::move(physics)),
      parser_(layout.protocol, PacketParser::Role::kDevice),
      rng_(common.faults.seed) {}

std::uint32_t VirtualBusCore::load(const RegisterFile& mem, std::uint16_t address,
                                   std::uint8_t size) {
  std::uint32_t v = 0;
  for (std::uint8_t i = 0; i < size; ++i)
    v |= static_cast<std::uint32_t>(mem[address + i]) << (8 * i);
  return v;
}

void VirtualBusCore::store(RegisterFile& mem, std::uint16_t address, std::uint8_t size,
                           std::uint32_t v) {
  for (std::uint8_t i = 0; i < size; ++i)
    mem[address + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

void VirtualBusCore::start_clock() {
  last_advance_ns_ = monotonic_ns();
}

VirtualBusCore::Device* VirtualBusCore::find(std::uint8_t id) {
  for (Device& d : devices_) {
    if (d.mem[layout_.id] == id) return &d;
  }
  return nullptr;
}

const VirtualBusCore::Device* VirtualBusCore::find(std::uint8_t id) const {
  for (const Device& d : devices_) {
    if (d.mem[layout_.id] == id) return &d;
  }
  return nullptr;
}

bool VirtualBusCore::faults_active() const {
  return counters_.bulk_reads + counters_.sync_reads >= faults_.start_after_cycles;
}

void VirtualBusCore::receive(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out,
                             std::int64_t& reply_delay_us) {
  Packet packet;
  std::size_t offset = 0;
  while (offset < bytes.size()) {
    offset += parser_.feed(bytes.subspan(offset));
    while (parser_.next(packet)) handle(packet, out, reply_delay_us);
    // A damaged packet addressed to a device may be answered with the checksum / CRC error.
    while (seen_bad_ < parser_.stats().bad_checksum) {
      ++seen_bad_;
      ++counters_.bad_packets;
      Device* d = find(parser_.last_bad_id());
      if (d != nullptr && parser_.last_bad_id() != kBroadcastId)
        on_bad_packet(*d, out, reply_delay_us);
    }
  }
}

void VirtualBusCore::handle(const Packet& packet, std::vector<std::uint8_t>& out,
                            std::int64_t& delay_us) {
  if (packet.is_status) return;
  ++counters_.instructions;
  advance_time(is_read_cycle(packet));
  dispatch(packet, out, delay_us);
}

void VirtualBusCore::advance_time(bool cycle) {
  const std::int64_t now = monotonic_ns();
  if (lockstep_) {
    if (cycle) physics_->advance(static_cast<double>(period_ns_) * 1e-9);
    last_advance_ns_ = now;
    return;
  }
  // After a long idle gap, do not integrate minutes at once.
  double dt = std::min(static_cast<double>(now - last_advance_ns_) * 1e-9, 2.0);
  last_advance_ns_ = now;
  while (dt > 1e-9) {
    const double step = std::min(dt, 0.005);
    physics_->advance(step);
    dt -= step;
  }
}

bool VirtualBusCore::reply(Device& device, std::uint8_t error, std::span<const std::uint8_t> params,
                           std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  const std::uint8_t id = status_id(device);
  if (faults_.silent[id] && faults_active()) {
    ++counters_.silenced;
    return false;
  }
  error = status_error(device, error);
  std::array<std::uint8_t, kMaxPacketBytes> packet{};
  const std::size_t n = encode_status(packet, id, error, params);
  if (n == 0) return false;
  if (faults_active() && !inject_reply_faults(faults_, rng_, {packet.data(), n}, counters_))
    return true;  // the device answered; the host never hears it (the chain goes on)
  delay_us += 2 * static_cast<std::int64_t>(device.mem[layout_.return_delay]);
  out.insert(out.end(), packet.begin(), packet.begin() + static_cast<std::ptrdiff_t>(n));
  ++counters_.replies;
  if (error != 0) ++counters_.error_replies;
  return true;
}

bool VirtualBusCore::read_reply(Device& device, std::uint16_t address, std::uint16_t length,
                                std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  if (device.mem[layout_.status_return_level] < 1) return true;
  refresh(device);
  std::uint8_t error = 0;
  if (read_refused(device, address, length, error)) return reply(device, error, {}, out, delay_us);
  return reply(device, 0, std::span<const std::uint8_t>(device.mem.data() + address, length), out,
               delay_us);
}

void VirtualBusCore::read_chain(std::span<const ReadRequest> requests,
                                std::vector<std::uint8_t>& out, std::int64_t& delay_us) {
  for (const ReadRequest& r : requests) {
    Device* d = find(r.id);
    if (d == nullptr || d->mem[layout_.status_return_level] < 1) {
      if (layout_.unanswered_ends_chain) break;
      continue;
    }
    if (!read_reply(*d, r.address, r.length, out, delay_us)) break;  // the next one waits
  }
}

void VirtualBusCore::sync_write(std::uint16_t address, std::uint16_t length,
                                std::span<const std::uint8_t> records) {
  for (std::size_t k = 0; k + 1 + length <= records.size(); k += 1U + length) {
    if (Device* d = find(records[k])) {
      (void)write(*d, address, records.subspan(k + 1, length));
      d->command_error = 0;  // no status packet carries it
    }
  }
}

void VirtualBusCore::register_write(Device& device, std::uint16_t address,
                                    std::span<const std::uint8_t> data) {
  device.registered = true;
  device.reg_address = address;
  device.reg_data.assign(data.begin(), data.end());
  device.mem[layout_.registered] = 1;
}

std::uint8_t VirtualBusCore::action(Device& device) {
  const std::uint8_t error = write(device, device.reg_address, device.reg_data);
  device.registered = false;
  device.mem[layout_.registered] = 0;
  return error;
}

PhysicsServoState VirtualBusCore::servo_state(const Device& device) const {
  PhysicsServoState s = physics_->servo_state(static_cast<std::size_t>(device.servo_index));
  if (faults_.overheat[status_id(device)] && faults_active()) s.temperature_c = 85.0;
  return s;
}

void VirtualBusCore::command(const Device& device, PhysicsServoCommand c) {
  const auto i = static_cast<std::size_t>(device.servo_index);
  const double q = physics_->servo_state(i).position_rad;
  while (c.goal_rad - q > units::kPi) c.goal_rad -= 2.0 * units::kPi;
  while (c.goal_rad - q < -units::kPi) c.goal_rad += 2.0 * units::kPi;
  physics_->set_command(i, c);
}

}  // namespace stride::hal::dxl
