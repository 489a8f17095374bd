// VirtualBusV2: 20 emulated MX-64(2.0)/MX-106(2.0) servos speaking Dynamixel protocol 2.0, for
// bench work with `stride dxl --protocol 2` and for testing the 2.0 codec end to end. (The
// igus robot's CM730 speaks 1.0 only, so this bus has no CM730; see VirtualBus for 1.0.)
//
// Behaviour: PING (model number + firmware), READ, WRITE, REG_WRITE/ACTION, SYNC_READ,
// SYNC_WRITE, BULK_READ, REBOOT (RAM to initial values), FACTORY_RESET with the e-manual's
// options (0xFF everything, 0x01 all but the ID, 0x02 all but the ID and the baud rate; 0xFF
// to the broadcast ID is not executed); status return level (68), return delay (9); broadcast
// PING answered by every servo in ID order; 2.0 error field: CRC, instruction, data range
// (value outside the register's range, or an unknown FACTORY_RESET option), data limit (Goal
// Position outside [Min Position Limit (52), Max Position Limit (48)] in position control
// mode; not applied), data length, access (read-only register, or EEPROM while torque is on),
// alert bit with the hardware error status (70) set while the temperature is above its limit
// (31). Faults and counters as VirtualBus (virtual_bus_faults.hpp); a read cycle is a
// SYNC_READ or BULK_READ, and a silent servo silences the rest of its list. Motion from a
// VirtualBusPhysics: goal position (116), profile velocity (112, 0.229 rpm), position P gain
// (84, mapped to the 1.0 P register as P/16, since K_PP = P/128 and Kp = P1/8), torque enable.
// Time: lockstep (one period per SYNC_READ/BULK_READ) or wall clock, as VirtualBus.
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

class VirtualBusV2 final : public BusResponder {
 public:
  struct Options {
    std::array<ServoCalibration, kServoCount> calibration{};
    bool lockstep = false;
    std::int64_t period_ns = 10'000'000;
    VirtualBusFaults faults{};
  };

  VirtualBusV2(const Options& options, std::unique_ptr<VirtualBusPhysics> physics);

  /// Consumes host bytes and appends replies to `out` (see VirtualBus::receive).
  void receive(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out,
               std::int64_t& reply_delay_us) override;
  const VirtualBusCounters& counters() const { return counters_; }
  /// Register value (little-endian, `size` bytes) of servo `id`, 0 if absent.
  std::uint32_t peek(std::uint8_t id, std::uint16_t address, std::uint8_t size) const;

 private:
  struct Servo {
    std::size_t index = 0;
    const ControlTable* table = nullptr;
    std::array<std::uint8_t, 256> mem{};
    bool registered = false;
    std::uint16_t reg_address = 0;
    std::vector<std::uint8_t> reg_data;
  };

  void handle(const Packet& packet, std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  /// Broadcast SYNC_READ (`code`; replies in list order) or SYNC_WRITE (no replies).
  void handle_sync(std::uint8_t code, std::span<const std::uint8_t> params,
                   std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  /// Broadcast BULK_READ: each listed servo answers after its predecessor's status packet.
  void handle_bulk_read(std::span<const std::uint8_t> params, std::vector<std::uint8_t>& out,
                        std::int64_t& delay_us);
  Servo* find(std::uint8_t id);
  void reset(Servo& servo, bool ram_only);
  /// FACTORY_RESET with a valid option (0xFF, 0x01 or 0x02).
  void factory_reset(Servo& servo, std::uint8_t option);
  void refresh(Servo& servo);
  void push_command(Servo& servo);
  std::uint8_t write(Servo& servo, std::uint16_t address, std::span<const std::uint8_t> data);
  /// Sends a status packet (subject to faults). Returns false if the servo stayed silent.
  bool reply(Servo& servo, std::uint8_t error, std::span<const std::uint8_t> params,
             std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  bool read_reply(Servo& servo, std::uint16_t address, std::uint16_t length,
                  std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  void advance_time(bool cycle);
  bool faults_active() const;

  Options options_;
  std::unique_ptr<VirtualBusPhysics> physics_;
  PacketParser parser_{Protocol::kV2, PacketParser::Role::kDevice};
  std::vector<Servo> servos_;
  std::int64_t last_advance_ns_ = 0;
  std::uint64_t seen_bad_ = 0;
  VirtualBusCounters counters_{};
  std::mt19937_64 rng_;
};

}  // namespace stride::hal::dxl
