// VirtualBus: an emulated Dynamixel protocol 1.0 bus with 20 MX-64/MX-106 servos and the CM730
// (ID 200) with the stock firmware or NimbRo's (Options::cm730_profile: 16-bit IMU registers and
// a magnetometer), each with its control table (control_table.hpp) and behaviour:
//  - PING, READ, WRITE, REG_WRITE, ACTION, RESET, SYNC_WRITE and the CM730-style BULK_READ;
//  - status return level (0: ping only, 1: + reads, 2: all), return delay time (reported per
//    reply in `reply_delay_us` so a server can wait it out), broadcast ID without replies;
//  - error bits: angle limit (goal outside CW/CCW limits, not applied), range (value outside a
//    register's range, not applied), overheating (temperature above its limit), overload
//    (load saturated at the torque limit), checksum (a damaged packet addressed to the device),
//    instruction (unknown instruction, ACTION without REG_WRITE);
//  - alarm shutdown: while an error bit in the Shutdown register (18) is active, torque is off;
//  - BULK_READ replies in list order, and, as on the real bus, a device answers only after its
//    predecessor's status packet: a device that stays silent silences the rest of the list.
// Motion and the IMU come from a VirtualBusPhysics. Time: in lockstep mode the physics advances
// by exactly one control period at each BULK_READ (the firmware's per-tick read), so a run is
// deterministic; otherwise it advances by the wall-clock time elapsed since the last packet.
// Faults (dropped or corrupted replies, silent or overheating servos) are injectable, seeded.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <random>
#include <span>
#include <vector>

#include "stride/hal/dynamixel/bus_responder.hpp"
#include "stride/hal/dynamixel/control_table.hpp"
#include "stride/hal/dynamixel/packet_parser.hpp"
#include "stride/hal/dynamixel/units.hpp"
#include "stride/hal/dynamixel/virtual_bus_faults.hpp"
#include "stride/hal/dynamixel/virtual_bus_physics.hpp"
#include "stride/hal/types.hpp"

namespace stride::hal::dxl {

class VirtualBus final : public BusResponder {
 public:
  struct Options {
    std::array<ServoCalibration, kServoCount> calibration{};  ///< per servo, index = id - 1
    bool lockstep = false;
    Cm730Profile cm730_profile = Cm730Profile::kStock;  ///< the CM730's table
    std::int64_t period_ns = 10'000'000;  ///< physics step per BULK_READ in lockstep mode
    VirtualBusFaults faults{};
  };

  VirtualBus(const Options& options, std::unique_ptr<VirtualBusPhysics> physics);

  /// Consumes bytes from the host and appends any replies to `out`. `reply_delay_us` receives
  /// the summed return delay time of the replies produced (0 after start-up configuration).
  void receive(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out,
               std::int64_t& reply_delay_us) override;

  const VirtualBusCounters& counters() const { return counters_; }
  VirtualBusPhysics& physics() { return *physics_; }
  /// Register byte of device `id` (for tests and `stride vbus` status), 0 if absent.
  std::uint8_t peek(std::uint8_t id, std::uint8_t address) const;

 private:
  struct Device {
    std::uint8_t id = 0;
    const ControlTable* table = nullptr;
    int servo_index = -1;  ///< -1 for the CM730
    std::array<std::uint8_t, 256> mem{};
    std::uint8_t command_error = 0;  ///< instruction/range/angle/checksum bits of this reply
    bool registered = false;
    std::uint8_t reg_address = 0;
    std::vector<std::uint8_t> reg_data;
  };

  /// One instruction packet: counts it, advances the clock, and hands it to the one below.
  void handle(const Packet& packet, std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  /// Broadcast SYNC_WRITE: every listed device writes its record; nobody answers.
  void handle_sync_write(std::span<const std::uint8_t> params);
  /// Broadcast BULK_READ: the listed devices answer in order (and a lockstep bus advances the
  /// physics by one period first); the chain stops at a device that is silent.
  void handle_bulk_read(std::span<const std::uint8_t> params, std::vector<std::uint8_t>& out,
                        std::int64_t& delay_us);
  /// Other broadcasts (WRITE, REG_WRITE, ACTION, RESET): every device executes, nobody answers.
  void handle_broadcast(const Packet& packet, std::span<const std::uint8_t> params);
  /// An instruction to one device, answered as its status return level says.
  void handle_addressed(const Packet& packet, std::span<const std::uint8_t> params,
                        std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  Device* find(std::uint8_t id);
  void reset_device(Device& device);
  void refresh(Device& device);
  void push_command(Device& device);
  std::uint8_t status_error(Device& device);
  bool apply_write(Device& device, std::uint8_t address, std::span<const std::uint8_t> data);
  /// Sends a status packet (subject to faults). Returns false if nothing went on the wire.
  bool reply(Device& device, std::span<const std::uint8_t> params, std::vector<std::uint8_t>& out,
             std::int64_t& delay_us);
  void advance_time();
  bool faults_active() const;

  Options options_;
  std::unique_ptr<VirtualBusPhysics> physics_;
  PacketParser parser_{Protocol::kV1, PacketParser::Role::kDevice};
  std::vector<Device> devices_;
  VirtualBusCounters counters_{};
  std::mt19937_64 rng_;
  std::int64_t last_advance_ns_ = 0;
  std::uint64_t seen_bad_checksum_ = 0;
};

}  // namespace stride::hal::dxl
