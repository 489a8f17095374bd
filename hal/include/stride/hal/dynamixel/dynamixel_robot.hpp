// DynamixelRobot: the HAL on the igus robot's Dynamixel bus (protocol 1.0, CM730 + 20 MX servos).
//
// Start-up (create): switches the CM730's Dynamixel power on, sets every device's return delay
// to 0 and its status return level (default 1: replies to PING and READ only) by broadcast,
// pings the 20 servos and the CM730 and reads their model numbers, and checks them against the
// servo table. A missing device or a wrong model is an error naming it (unless allow_missing,
// which starts with the device marked missing and retried later).
//
// Each tick:
//  - write(): one SYNC_WRITE from P gain (28): [P, 0 (reserved 29), goal(2), moving speed(2),
//    torque limit(2)] for only the servos whose bytes changed (or were last sent more than
//    refresh_interval_ticks ago, so a lost packet heals). Torque enable (24) and the D/I gains
//    (26, 27), which rarely change, go in extra SYNC_WRITEs only on ticks where they change
//    (starting at 28 instead of NUbots' 26 saves 40 bytes per tick for 20 servos, which keeps
//    the 100 Hz cycle within 60 % of the period at 1 Mbaud). A non-finite goal turns that
//    servo's torque off.
//  - read(): one BULK_READ: CM730 21 bytes from 30 (button .. voltage), each servo 8 bytes from
//    36 (position, speed, load, voltage, temperature); fills the SensorFrame with values,
//    error flags and health. The CM730's bytes are decoded by its firmware's table
//    (Options::cm730_profile): the stock ROBOTIS one (10-bit IMU) or NimbRo's (16-bit IMU and
//    a magnetometer in the same 21 bytes, igus.md 6.5); start-up checks the CM730's model
//    number against the profile, so a board with the other firmware is an error naming both.
// Failure policy: a BULK_READ reply chain stops at the first device that does not answer, so
// that device is blamed (consecutive_failures + 1) and moved to the end of the list; after
// max_consecutive_failures it is skipped (health kMissing) and tried again every
// retry_interval_ticks. Every transaction's deadline is its bytes' wire time at the baud rate
// plus the devices' return delays plus margin_ns, and never later than bus_budget_fraction of
// the period after the cycle started: the loop is never held past its budget.
// The budget of a cycle starts at read(); TX/RX times of the cycle are in diagnostics().
// Real-time: after create(), no allocation, no exceptions; blocking is bounded by deadlines.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "stride/core/status.hpp"
#include "stride/hal/dynamixel/byte_stream.hpp"
#include "stride/hal/dynamixel/control_table.hpp"
#include "stride/hal/dynamixel/packet_parser.hpp"
#include "stride/hal/dynamixel/protocol.hpp"
#include "stride/hal/dynamixel/units.hpp"
#include "stride/hal/robot.hpp"

namespace stride::hal::dxl {

class DynamixelRobot final : public Robot {
 public:
  struct Options {
    std::int64_t period_ns = 10'000'000;
    std::array<ServoCalibration, kServoCount> calibration{};
    std::array<std::string, kServoCount> names{};  ///< joint names, for messages
    std::uint8_t status_return_level = 1;
    Cm730Profile cm730_profile = Cm730Profile::kStock;  ///< the CM730 firmware's table
    std::int64_t margin_ns = 1'500'000;  ///< added to every transaction's computed time
    /// Start-up (start()) only: how long a ping or register read waits past its wire time.
    /// Outside the loop nothing is budgeted, so it is generous: a real device answers within
    /// its return delay (<= 0.5 ms), but a device emulated by another process (stride vbus on
    /// a pty) may wait for a core on a loaded host. A missing device costs ping_retries x this.
    std::int64_t startup_reply_wait_ns = 25'000'000;
    double bus_budget_fraction = 0.6;  ///< read+write must finish within this part of a period
    std::uint32_t max_consecutive_failures = 5;
    std::uint32_t retry_interval_ticks = 50;
    std::uint32_t refresh_interval_ticks = 100;
    int ping_retries = 3;
    bool allow_missing = false;
    /// true: sleep_until() waits on CLOCK_MONOTONIC itself. false: it only records the tick
    /// (an outer pacer such as the firmware's RealtimeRobot does the waiting).
    bool self_paced = true;
  };

  /// Runs the start-up sequence on `stream`. The error names missing devices / wrong models.
  static Status create(std::unique_ptr<ByteStream> stream, const Options& options,
                       std::unique_ptr<DynamixelRobot>& out);

  std::int64_t period_ns() const noexcept override { return options_.period_ns; }
  Tick sleep_until(Tick tick) noexcept override;
  void read(SensorFrame& out) noexcept override;
  void write(const CommandFrame& commands) noexcept override;
  void set_torque_enable(bool enabled) noexcept override;
  const Diagnostics& diagnostics() const noexcept override { return diagnostics_; }

  /// Human-readable device list after start-up ("20 servos + CM730 found ..."), not real-time.
  const std::string& startup_report() const { return startup_report_; }
  /// One line per unhealthy device with its counters, naming it ("7 r_hip_yaw: 12 timeouts");
  /// empty when every device is healthy. Not real-time (allocates).
  std::string health_report() const;
  /// Display name of diagnostics index `index` (0..19 servo names, 20 "CM730").
  std::string device_name(std::size_t index) const;
  const PacketParser::Stats& parser_stats() const { return parser_.stats(); }

 private:
  static constexpr std::size_t kDevices = kServoCount + 1;
  static constexpr std::size_t kCm730Index = kServoCount;
  static constexpr std::uint8_t kCm730ReadAddress = 30;
  static constexpr std::uint8_t kCm730ReadLength = 21;
  static constexpr std::uint8_t kServoReadAddress = 36;
  static constexpr std::uint8_t kServoReadLength = 8;
  static constexpr std::uint8_t kSyncAddress = 28;
  static constexpr std::uint8_t kSyncLength = 8;
  static constexpr std::uint8_t kGainAddress = 26;  ///< D, I

  DynamixelRobot(std::unique_ptr<ByteStream> stream, const Options& options);
  Status start();
  static std::uint8_t device_id(std::size_t index);

  /// Sends `packet` and, if `expect_reply`, waits for a status packet from `id`.
  bool transact(std::span<const std::uint8_t> packet, std::uint8_t id, bool expect_reply,
                std::size_t reply_params, Packet* reply) noexcept;
  bool send(std::span<const std::uint8_t> packet, std::int64_t deadline_ns) noexcept;
  void decode_servo(std::size_t index, const std::uint8_t* data) noexcept;
  void decode_cm730(const std::uint8_t* data) noexcept;

  /// One tick's BULK_READ: who is asked, in which order, and what came back.
  struct BulkRound {
    std::array<BulkReadEntry, kDevices> entries{};
    std::array<std::uint8_t, kDevices> device{};  ///< device index of each entry
    std::array<bool, kDevices> got{};             ///< a whole reply came
    std::array<bool, kDevices> corrupt{};         ///< a damaged reply came
    std::size_t count = 0;
  };
  /// The list: active devices in order_, then skipped ones due for a retry.
  void plan_bulk_read(BulkRound& round) const noexcept;
  /// Sends the BULK_READ and decodes the replies until the last one or the cycle's bus budget.
  void exchange_bulk_read(BulkRound& round) noexcept;
  /// Health and the failure policy: the first device that did not answer is blamed, moved to
  /// the end of the list, and skipped after options_.max_consecutive_failures.
  void judge_bulk_read(const BulkRound& round) noexcept;

  std::unique_ptr<ByteStream> stream_;
  Options options_;
  PacketParser parser_{Protocol::kV1, PacketParser::Role::kHost};
  Packet packet_{};
  Diagnostics diagnostics_{};
  SensorFrame state_{};
  std::array<std::uint8_t, kDevices> order_{};  ///< bulk-read order (device indices)
  std::array<bool, kDevices> skipped_{};
  std::array<std::array<std::uint8_t, kSyncLength>, kServoCount> sent_bytes_{};
  std::array<Tick, kServoCount> sent_tick_{};
  std::array<bool, kServoCount> sent_once_{};
  std::array<std::int8_t, kServoCount> torque_sent_{};                 ///< -1 unknown, 0 off, 1 on
  std::array<std::array<std::uint8_t, 2>, kServoCount> gains_sent_{};  ///< D, I
  std::array<bool, kServoCount> gains_sent_once_{};
  std::array<std::uint8_t, kMaxPacketBytes> tx_{};
  std::array<std::uint8_t, 512> rx_{};
  std::int64_t start_ns_ = -1;
  std::int64_t cycle_start_ns_ = 0;
  Tick tick_ = 0;
  std::string startup_report_;
};

/// Opens `port` at `baud` (SerialPort) and runs DynamixelRobot::create on it.
Status open_dynamixel_robot(const std::string& port, std::uint32_t baud,
                            const DynamixelRobot::Options& options,
                            std::unique_ptr<DynamixelRobot>& out);

}  // namespace stride::hal::dxl
