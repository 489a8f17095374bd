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
// What the two buses share (dispatch skeleton, read chains, faults, clock, replies) is in
// VirtualBusCore; this class holds protocol 1.0's packets, instructions and registers.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "stride/hal/dynamixel/control_table.hpp"
#include "stride/hal/dynamixel/virtual_bus_core.hpp"

namespace stride::hal::dxl {

class VirtualBus final : public VirtualBusCore {
 public:
  struct Options {
    std::array<ServoCalibration, kServoCount> calibration{};  ///< per servo, index = id - 1
    bool lockstep = false;
    Cm730Profile cm730_profile = Cm730Profile::kStock;  ///< the CM730's table
    std::int64_t period_ns = 10'000'000;  ///< physics step per BULK_READ in lockstep mode
    VirtualBusFaults faults{};
  };

  VirtualBus(const Options& options, std::unique_ptr<VirtualBusPhysics> physics);

  /// Register byte of device `id` (for tests and `stride vbus` status), 0 if absent.
  std::uint8_t peek(std::uint8_t id, std::uint8_t address) const;

 private:
  void dispatch(const Packet& packet, std::vector<std::uint8_t>& out,
                std::int64_t& delay_us) override;
  bool is_read_cycle(const Packet& packet) const override;
  void on_bad_packet(Device& device, std::vector<std::uint8_t>& out,
                     std::int64_t& delay_us) override;
  std::uint8_t status_id(const Device& device) const override { return device.id; }
  std::uint8_t status_error(Device& device, std::uint8_t error) override;
  std::size_t encode_status(std::span<std::uint8_t> out, std::uint8_t id, std::uint8_t error,
                            std::span<const std::uint8_t> params) override;
  void refresh(Device& device) override;
  std::uint8_t write(Device& device, std::uint16_t address,
                     std::span<const std::uint8_t> data) override;
  bool read_refused(Device& device, std::uint16_t address, std::uint16_t length,
                    std::uint8_t& error) override;

  /// Broadcast SYNC_WRITE: every listed device writes its record; nobody answers.
  void handle_sync_write(std::span<const std::uint8_t> params);
  /// Broadcast BULK_READ: the listed devices answer in order; the chain stops at a device that
  /// is silent, absent or at status return level 0.
  void handle_bulk_read(std::span<const std::uint8_t> params, std::vector<std::uint8_t>& out,
                        std::int64_t& delay_us);
  /// Other broadcasts (WRITE, REG_WRITE, ACTION, RESET): every device executes, nobody answers.
  void handle_broadcast(const Packet& packet, std::span<const std::uint8_t> params);
  /// An instruction to one device, answered as its status return level says.
  void handle_addressed(const Packet& packet, std::span<const std::uint8_t> params,
                        std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  void reset_device(Device& device);
  void refresh_cm730(Device& device);
  void push_command(Device& device);
  /// The hardware error bits (input voltage, overheating, overload) and the held command bits.
  std::uint8_t device_error(const Device& device) const;

  Cm730Profile cm730_profile_;
};

}  // namespace stride::hal::dxl
