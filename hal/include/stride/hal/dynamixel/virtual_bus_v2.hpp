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
// Time: lockstep (one period per SYNC_READ/BULK_READ) or wall clock, as VirtualBus. What the
// two buses share is in VirtualBusCore; this class holds protocol 2.0's packets, instructions
// and registers.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "stride/hal/dynamixel/virtual_bus_core.hpp"

namespace stride::hal::dxl {

class VirtualBusV2 final : public VirtualBusCore {
 public:
  using Options = VirtualBusCore::Options;  ///< calibration, lockstep, period, faults

  VirtualBusV2(const Options& options, std::unique_ptr<VirtualBusPhysics> physics);

  /// Register value (little-endian, `size` bytes) of servo `id`, 0 if absent.
  std::uint32_t peek(std::uint8_t id, std::uint16_t address, std::uint8_t size) const;

 private:
  void dispatch(const Packet& packet, std::vector<std::uint8_t>& out,
                std::int64_t& delay_us) override;
  bool is_read_cycle(const Packet& packet) const override;
  void on_bad_packet(Device& device, std::vector<std::uint8_t>& out,
                     std::int64_t& delay_us) override;
  std::uint8_t status_id(const Device& device) const override;
  std::uint8_t status_error(Device& device, std::uint8_t error) override;
  std::size_t encode_status(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t error,
                            std::span<const std::uint8_t> params) override;
  void refresh(Device& device) override;
  std::uint8_t write(Device& device, std::uint16_t address,
                     std::span<const std::uint8_t> data) override;
  bool read_refused(Device& device, std::uint16_t address, std::uint16_t length,
                    std::uint8_t& error) override;

  /// Broadcast SYNC_READ (`code`; replies in list order) or SYNC_WRITE (no replies).
  void handle_sync(std::uint8_t code, std::span<const std::uint8_t> params,
                   std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  /// Broadcast BULK_READ: each listed servo answers after its predecessor's status packet.
  void handle_bulk_read(std::span<const std::uint8_t> params, std::vector<std::uint8_t>& out,
                        std::int64_t& delay_us);
  /// READ, WRITE, REG_WRITE, ACTION, REBOOT, FACTORY_RESET to one servo or all of them.
  void handle_each(const Packet& packet, std::span<const std::uint8_t> params,
                   std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  void reset(Device& servo, bool ram_only);
  /// FACTORY_RESET with a valid option (0xFF, 0x01 or 0x02).
  void factory_reset(Device& servo, std::uint8_t option);
  void push_command(Device& servo);
};

}  // namespace stride::hal::dxl
