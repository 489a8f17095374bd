// VirtualBusV2: 20 emulated MX-64(2.0)/MX-106(2.0) servos speaking Dynamixel protocol 2.0, for
// bench work with `stride dxl --protocol 2` and for testing the 2.0 codec end to end. (The
// igus robot's CM730 speaks 1.0 only, so this bus has no CM730; see VirtualBus for 1.0.)
//
// Behaviour: PING (model number + firmware), READ, WRITE, REG_WRITE/ACTION, SYNC_READ,
// SYNC_WRITE, BULK_READ, REBOOT (RAM to initial values), FACTORY_RESET (all but the ID);
// status return level (68), return delay (9); broadcast PING answered by every servo in ID
// order; 2.0 error field: CRC, instruction, data range (value outside the register's range),
// access (read-only register, or EEPROM while torque is on), alert bit with the hardware error
// status (70) set while the temperature is above its limit (31). Motion from a
// VirtualBusPhysics: goal position (116), profile velocity (112, 0.229 rpm), position P gain
// (84, mapped to the 1.0 P register as P/16, since K_PP = P/128 and Kp = P1/8), torque enable.
// Time: lockstep (one period per SYNC_READ/BULK_READ) or wall clock, as VirtualBus.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "stride/hal/dynamixel/bus_responder.hpp"
#include "stride/hal/dynamixel/control_table.hpp"
#include "stride/hal/dynamixel/packet_parser.hpp"
#include "stride/hal/dynamixel/units.hpp"
#include "stride/hal/dynamixel/virtual_bus_physics.hpp"
#include "stride/hal/types.hpp"

namespace stride::hal::dxl {

class VirtualBusV2 final : public BusResponder {
 public:
  struct Options {
    std::array<ServoCalibration, kServoCount> calibration{};
    bool lockstep = false;
    std::int64_t period_ns = 10'000'000;
    std::array<bool, 256> overheat{};  ///< these servos report 85 deg C
  };

  VirtualBusV2(const Options& options, std::unique_ptr<VirtualBusPhysics> physics);

  /// Consumes host bytes and appends replies to `out` (see VirtualBus::receive).
  void receive(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out,
               std::int64_t& reply_delay_us) override;
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
  Servo* find(std::uint8_t id);
  void reset(Servo& servo, bool ram_only);
  void refresh(Servo& servo);
  void push_command(Servo& servo);
  std::uint8_t write(Servo& servo, std::uint16_t address, std::span<const std::uint8_t> data);
  void reply(Servo& servo, std::uint8_t error, std::span<const std::uint8_t> params,
             std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  void read_reply(Servo& servo, std::uint16_t address, std::uint16_t length,
                  std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  void advance_time(bool cycle);

  Options options_;
  std::unique_ptr<VirtualBusPhysics> physics_;
  PacketParser parser_{Protocol::kV2, PacketParser::Role::kDevice};
  std::vector<Servo> servos_;
  std::int64_t last_advance_ns_ = 0;
  std::uint64_t seen_bad_ = 0;
};

}  // namespace stride::hal::dxl
