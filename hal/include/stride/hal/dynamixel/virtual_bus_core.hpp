// VirtualBusCore: the body the two emulated buses share (VirtualBus, protocol 1.0, and
// VirtualBusV2, protocol 2.0): the device list and lookup by the ID register, the receive loop
// (parser, damaged packets), the instruction skeleton (count, advance the clock, hand over),
// the read chain of BULK_READ / SYNC_READ that stops at a silent device, SYNC_WRITE records,
// registered writes and ACTION, fault injection and the counters, the clock (one period per
// read cycle in lockstep mode, else the wall-clock time since the last packet), the servo
// state from and the commands to the physics, and the status packet (silence, faults, return
// delay, counters).
//
// Idiom: an abstract base class whose protected hooks each protocol implements (packet format,
// instruction codes, register map, error bits). The buses are already used through the virtual
// BusResponder, so virtual hooks cost nothing new, the shared body stays in one source file
// rather than in a header-only template, and a shared core object composed into each bus would
// need the same hooks passed back to it as callbacks. The register addresses the core reads
// (ID, return delay, status return level, registered flag) come in a Layout.
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

class VirtualBusCore : public BusResponder {
 public:
  /// What every emulated bus is configured with (VirtualBusV2 takes it as it is).
  struct Options {
    std::array<ServoCalibration, kServoCount> calibration{};
    bool lockstep = false;
    std::int64_t period_ns = 10'000'000;
    VirtualBusFaults faults{};
  };

  /// Consumes bytes from the host and appends any replies to `out`. `reply_delay_us` receives
  /// the summed return delay time of the replies produced (0 after start-up configuration).
  void receive(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out,
               std::int64_t& reply_delay_us) final;

  const VirtualBusCounters& counters() const { return counters_; }
  VirtualBusPhysics& physics() { return *physics_; }

 protected:
  /// Where the core finds the registers it reads, and how the protocol's read chains behave.
  struct Layout {
    Protocol protocol = Protocol::kV1;
    std::uint16_t id = 0;
    std::uint16_t return_delay = 0;  ///< 2 us units
    std::uint16_t status_return_level = 0;
    std::uint16_t registered = 0;  ///< set while a REG_WRITE waits for ACTION
    /// 1.0 (the CM730's BULK_READ): an absent device or one at status return level 0 ends the
    /// chain; 2.0: it is skipped.
    bool unanswered_ends_chain = false;
  };
  struct Device {
    std::uint8_t id = 0;   ///< the ID it was created with (1.0 answers and faults use it)
    int servo_index = -1;  ///< -1 for the CM730
    const ControlTable* table = nullptr;
    std::array<std::uint8_t, 256> mem{};
    std::uint8_t command_error = 0;  ///< 1.0: instruction/range/angle/checksum bits
    bool registered = false;
    std::uint16_t reg_address = 0;
    std::vector<std::uint8_t> reg_data;
  };
  /// One request of a read chain (a BULK_READ entry, or a SYNC_READ ID with its range).
  using ReadRequest = BulkReadEntry;

  VirtualBusCore(const Options& common, const Layout& layout,
                 std::unique_ptr<VirtualBusPhysics> physics);

  // --- Hooks: what each protocol says for itself.
  /// An instruction packet, after it was counted and the clock advanced.
  virtual void dispatch(const Packet& packet, std::vector<std::uint8_t>& out,
                        std::int64_t& delay_us) = 0;
  /// Whether `packet` is a read cycle (lockstep: the physics advances one period first).
  virtual bool is_read_cycle(const Packet& packet) const = 0;
  /// A damaged packet that names device `device` (the core has counted it).
  virtual void on_bad_packet(Device& device, std::vector<std::uint8_t>& out,
                             std::int64_t& delay_us) = 0;
  /// The ID a status packet and the per-ID faults use.
  virtual std::uint8_t status_id(const Device& device) const = 0;
  /// The error byte / field of a status packet about to go out, from `error` and the device's
  /// state (clears any error the device held for it).
  virtual std::uint8_t status_error(Device& device, std::uint8_t error) = 0;
  virtual std::size_t encode_status(std::span<std::uint8_t> out, std::uint8_t id,
                                    std::uint8_t error, std::span<const std::uint8_t> params) = 0;
  /// Present values from the physics, hardware errors, alarm shutdown.
  virtual void refresh(Device& device) = 0;
  /// A register write, checked; returns the error to answer (1.0: 0, the bits go to the device).
  virtual std::uint8_t write(Device& device, std::uint16_t address,
                             std::span<const std::uint8_t> data) = 0;
  /// Whether a read of `length` bytes from `address` is refused; sets the error to answer.
  virtual bool read_refused(Device& device, std::uint16_t address, std::uint16_t length,
                            std::uint8_t& error) = 0;

  // --- The shared body.
  using RegisterFile = std::array<std::uint8_t, 256>;
  /// The little-endian value of `size` bytes at `address`.
  static std::uint32_t load(const RegisterFile& mem, std::uint16_t address, std::uint8_t size);
  static void store(RegisterFile& mem, std::uint16_t address, std::uint8_t size, std::uint32_t v);
  Device* find(std::uint8_t id);
  const Device* find(std::uint8_t id) const;
  /// Sends a status packet (subject to faults). Returns false if nothing went on the wire
  /// because the device is silent (or the packet could not be encoded).
  bool reply(Device& device, std::uint8_t error, std::span<const std::uint8_t> params,
             std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  /// A read answered as the device's status return level says (refreshed first).
  bool read_reply(Device& device, std::uint16_t address, std::uint16_t length,
                  std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  /// BULK_READ / SYNC_READ: the devices answer in list order, each after its predecessor's
  /// status packet, so the chain stops at a device that stays silent.
  void read_chain(std::span<const ReadRequest> requests, std::vector<std::uint8_t>& out,
                  std::int64_t& delay_us);
  /// SYNC_WRITE: records of [id][length bytes]; every listed device writes; nobody answers.
  void sync_write(std::uint16_t address, std::uint16_t length,
                  std::span<const std::uint8_t> records);
  /// REG_WRITE: keeps the write for ACTION.
  void register_write(Device& device, std::uint16_t address, std::span<const std::uint8_t> data);
  /// ACTION: runs the registered write; returns its error.
  std::uint8_t action(Device& device);
  /// The device's servo state, with an injected overheat.
  PhysicsServoState servo_state(const Device& device) const;
  /// Sends a command to the physics, its goal moved by whole turns to the side nearest the joint
  /// (the register's angle wraps into [-pi, pi)).
  void command(const Device& device, PhysicsServoCommand c);
  bool faults_active() const;
  /// Starts the wall clock (at the end of the bus's constructor).
  void start_clock();

  std::array<ServoCalibration, kServoCount> calibration_;
  std::vector<Device> devices_;
  VirtualBusCounters counters_{};

 private:
  void handle(const Packet& packet, std::vector<std::uint8_t>& out, std::int64_t& delay_us);
  void advance_time(bool cycle);

  bool lockstep_;
  std::int64_t period_ns_;
  VirtualBusFaults faults_;
  Layout layout_;
  std::unique_ptr<VirtualBusPhysics> physics_;
  PacketParser parser_;
  std::mt19937_64 rng_;
  std::int64_t last_advance_ns_ = 0;
  std::uint64_t seen_bad_ = 0;
};

}  // namespace stride::hal::dxl
