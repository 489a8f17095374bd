// DynamixelRobot implementation (see dynamixel_robot.hpp).
#include "stride/hal/dynamixel/dynamixel_robot.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <ctime>

#include "stride/hal/dynamixel/codec_v1.hpp"
#include "stride/hal/dynamixel/control_table.hpp"
#include "stride/hal/dynamixel/serial_port.hpp"

namespace stride::hal::dxl {

namespace {

void sleep_ns(std::int64_t ns) {
  timespec ts{static_cast<time_t>(ns / 1'000'000'000LL), static_cast<long>(ns % 1'000'000'000LL)};
  while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
  }
}

std::string model_name(std::uint16_t model) {
  const ControlTable* t = table_for_model(model, Protocol::kV1);
  return t != nullptr ? std::string(t->model_name) + " (" + std::to_string(model) + ")"
                      : "unknown model " + std::to_string(model);
}

}  // namespace

DynamixelRobot::DynamixelRobot(std::unique_ptr<ByteStream> stream, const Options& options)
    : stream_(std::move(stream)), options_(options) {
  order_[0] = kCm730Index;
  for (std::size_t i = 0; i < kServoCount; ++i) order_[i + 1] = static_cast<std::uint8_t>(i);
  torque_sent_.fill(-1);
}

std::uint8_t DynamixelRobot::device_id(std::size_t index) {
  return index == kCm730Index ? kCm730Id : static_cast<std::uint8_t>(index + 1);
}

std::string DynamixelRobot::device_name(std::size_t index) const {
  if (index == kCm730Index) return "200 CM730";
  const std::string& name = options_.names[index];
  return std::to_string(index + 1) + (name.empty() ? "" : " " + name);
}

Status DynamixelRobot::create(std::unique_ptr<ByteStream> stream, const Options& options,
                              std::unique_ptr<DynamixelRobot>& out) {
  if (!stream) return Status::error("dynamixel: no byte stream");
  if (options.period_ns <= 0) return Status::error("dynamixel: period must be > 0");
  if (options.status_return_level > 2) {
    return Status::error("dynamixel: status return level must be 0, 1 or 2");
  }
  if (options.status_return_level == 0) {
    return Status::error("dynamixel: status return level 0 disables BULK_READ replies; use 1 or 2");
  }
  std::unique_ptr<DynamixelRobot> robot(new DynamixelRobot(std::move(stream), options));
  if (Status s = robot->start(); !s) return s;
  out = std::move(robot);
  return {};
}

bool DynamixelRobot::send(std::span<const std::uint8_t> packet, std::int64_t deadline_ns) noexcept {
  const std::int64_t t0 = monotonic_ns();
  const bool ok = stream_->write(packet, deadline_ns);
  const std::int64_t dt = monotonic_ns() - t0;
  diagnostics_.last_tx_ns += dt;
  diagnostics_.bytes_tx += packet.size();
  return ok;
}

bool DynamixelRobot::transact(std::span<const std::uint8_t> packet, std::uint8_t id,
                              bool expect_reply, std::size_t reply_params, Packet* reply) noexcept {
  stream_->discard_input();
  parser_.reset();
  const std::uint32_t baud = stream_->baud();
  const std::int64_t now = monotonic_ns();
  const std::int64_t tx_deadline = now + wire_time_ns(packet.size(), baud) + options_.margin_ns;
  if (!send(packet, tx_deadline)) return false;
  if (!expect_reply) return true;
  // Start-up replies may still come with the factory return delay (250 * 2 us); the wait is
  // the start-up one, not the loop's margin (nothing is budgeted before the loop runs).
  const std::int64_t deadline = monotonic_ns() + wire_time_ns(packet.size(), baud) +
                                wire_time_ns(6 + reply_params, baud) + 500'000 +
                                std::max(options_.margin_ns, options_.startup_reply_wait_ns);
  for (;;) {
    while (parser_.next(packet_)) {
      diagnostics_.bytes_rx += 0;
      if (packet_.id == id) {
        if (reply != nullptr) *reply = packet_;
        return true;
      }
    }
    const std::ptrdiff_t n = stream_->read_some(rx_, deadline);
    if (n <= 0) return false;
    diagnostics_.bytes_rx += static_cast<std::uint64_t>(n);
    (void)parser_.feed(std::span<const std::uint8_t>(rx_.data(), static_cast<std::size_t>(n)));
  }
}

Status DynamixelRobot::start() {
  std::array<std::uint8_t, 64> tx{};
  Packet reply;
  auto ping = [&](std::uint8_t id) {
    for (int attempt = 0; attempt < std::max(1, options_.ping_retries); ++attempt) {
      const std::size_t n = v1::encode_ping(tx, id);
      if (transact(std::span(tx.data(), n), id, true, 0, &reply)) return true;
    }
    return false;
  };
  auto read_u16_reg = [&](std::uint8_t id, std::uint8_t address, std::uint16_t& value) {
    for (int attempt = 0; attempt < std::max(1, options_.ping_retries); ++attempt) {
      const std::size_t n = v1::encode_read(tx, id, address, 2);
      if (transact(std::span(tx.data(), n), id, true, 2, &reply) && reply.param_count == 2) {
        value = read_u16(reply.params.data());
        return true;
      }
    }
    return false;
  };

  // CM730 first: its Dynamixel power switch feeds the servos.
  std::string missing;
  const bool cm730_found = ping(kCm730Id);
  if (cm730_found) {
    std::uint16_t power = 0;
    const std::size_t n = v1::encode_read(tx, kCm730Id, cm730::kDxlPower, 1);
    if (transact(std::span(tx.data(), n), kCm730Id, true, 1, &reply) && reply.param_count == 1) {
      power = reply.params[0];
    }
    if (power == 0) {
      const std::uint8_t on = 1;
      const std::size_t w = v1::encode_write(tx, kCm730Id, cm730::kDxlPower, std::span(&on, 1));
      (void)transact(std::span(tx.data(), w), kCm730Id, true, 0, nullptr);
      sleep_ns(100'000'000);  // let the servos boot
    }
  }
  // Broadcast: return delay 0, status return level. No replies to broadcasts.
  const std::uint8_t zero = 0;
  std::size_t n = v1::encode_write(tx, kBroadcastId, mx1::kReturnDelayTime, std::span(&zero, 1));
  (void)transact(std::span(tx.data(), n), kBroadcastId, false, 0, nullptr);
  n = v1::encode_write(tx, kBroadcastId, mx1::kStatusReturnLevel,
                       std::span(&options_.status_return_level, 1));
  (void)transact(std::span(tx.data(), n), kBroadcastId, false, 0, nullptr);
  sleep_ns(2'000'000);  // EEPROM writes

  std::string report;
  std::string wrong;
  std::size_t found = 0;
  for (std::size_t i = 0; i < kDevices; ++i) {
    const std::uint8_t id = device_id(i);
    DeviceDiagnostics& d = diagnostics_.devices[i];
    const bool present = i == kCm730Index ? cm730_found : ping(id);
    std::uint16_t model = 0;
    if (!present || !read_u16_reg(id, mx1::kModelNumber, model)) {
      missing += (missing.empty() ? "" : ", ") + device_name(i);
      d.health = DeviceHealth::kMissing;
      skipped_[i] = true;
      continue;
    }
    const std::uint16_t expected = i == kCm730Index
                                       ? cm730_table(options_.cm730_profile).model_number
                                       : model_number_v1(options_.calibration[i].model);
    if (model != expected) {
      wrong += (wrong.empty() ? "" : ", ") + device_name(i) + " is " + model_name(model) +
               (i == kCm730Index
                    ? std::string(", --cm730 ") + to_string(options_.cm730_profile) + " expects "
                    : std::string(", servo table says ")) +
               model_name(expected);
      continue;
    }
    d.health = DeviceHealth::kOk;
    ++found;
  }
  report = std::to_string(found) + " of 21 devices found";
  if (!missing.empty()) report += "; missing: " + missing;
  startup_report_ = report;
  if (!wrong.empty()) return Status::error("dynamixel: wrong model: " + wrong);
  if (!missing.empty() && !options_.allow_missing) {
    return Status::error("dynamixel: missing devices: " + missing);
  }
  diagnostics_.last_tx_ns = 0;
  for (std::size_t i = 0; i < kServoCount; ++i)
    state_.servos[i].health = diagnostics_.devices[i].health;
  state_.cm730.health = diagnostics_.devices[kCm730Index].health;
  return {};
}

Tick DynamixelRobot::sleep_until(Tick tick) noexcept {
  if (!options_.self_paced) {
    tick_ = tick;
    return tick;
  }
  if (start_ns_ < 0) start_ns_ = monotonic_ns() - tick * options_.period_ns;
  const std::int64_t target = start_ns_ + tick * options_.period_ns;
  const timespec ts{static_cast<time_t>(target / 1'000'000'000LL),
                    static_cast<long>(target % 1'000'000'000LL)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
  const std::int64_t late = monotonic_ns() - target;
  tick_ = tick + (late > 0 ? late / options_.period_ns : 0);
  return tick_;
}

void DynamixelRobot::decode_servo(std::size_t i, const std::uint8_t* data) noexcept {
  const ServoCalibration& cal = options_.calibration[i];
  ServoState& s = state_.servos[i];
  s.position_rad = units::ticks_to_position(read_u16(data), cal);
  s.speed_rad_s = units::present_speed_from_register(read_u16(data + 2), cal);
  s.load = units::load_from_register(read_u16(data + 4), cal);
  s.voltage_v = units::voltage_from_register(data[6]);
  s.temperature_c = units::temperature_from_register(data[7]);
}

void DynamixelRobot::decode_cm730(const std::uint8_t* data) noexcept {
  // data[k] is address 30 + k.
  auto at = [&](std::uint8_t address) { return read_u16(data + (address - kCm730ReadAddress)); };
  Cm730State& c = state_.cm730;
  c.buttons = data[0];
  if (options_.cm730_profile == Cm730Profile::kNimbro) {
    namespace n = cm730_nimbro;
    c.gyro_rad_s = {units::nimbro_gyro_from_raw(at(n::kGyroX)),
                    units::nimbro_gyro_from_raw(at(n::kGyroY)),
                    units::nimbro_gyro_from_raw(at(n::kGyroZ))};
    c.accel_mps2 = {units::nimbro_accel_from_raw(at(n::kAccelX)),
                    units::nimbro_accel_from_raw(at(n::kAccelY)),
                    units::nimbro_accel_from_raw(at(n::kAccelZ))};
    c.mag_gauss = {units::nimbro_mag_from_raw(at(n::kMagX)),
                   units::nimbro_mag_from_raw(at(n::kMagY)),
                   units::nimbro_mag_from_raw(at(n::kMagZ))};
    c.has_magnetometer = true;
    c.voltage_v = units::voltage_from_register(data[n::kBatteryVoltage - kCm730ReadAddress]);
    return;
  }
  c.gyro_rad_s = {units::gyro_from_raw(at(cm730::kGyroX)), units::gyro_from_raw(at(cm730::kGyroY)),
                  units::gyro_from_raw(at(cm730::kGyroZ))};
  c.accel_mps2 = {units::accel_from_raw(at(cm730::kAccelX)),
                  units::accel_from_raw(at(cm730::kAccelY)),
                  units::accel_from_raw(at(cm730::kAccelZ))};
  c.voltage_v = units::voltage_from_register(data[cm730::kVoltage - kCm730ReadAddress]);
}

void DynamixelRobot::plan_bulk_read(BulkRound& round) const noexcept {
  // Active devices in order_, then skipped devices due for a retry.
  const Tick tick = tick_;
  for (int pass = 0; pass < 2; ++pass) {
    for (const std::uint8_t i : order_) {
      const bool retry_due =
          options_.retry_interval_ticks > 0 &&
          (tick + static_cast<Tick>(i)) % static_cast<Tick>(options_.retry_interval_ticks) == 0;
      const bool include = pass == 0 ? !skipped_[i] : (skipped_[i] && retry_due);
      if (!include) continue;
      round.entries[round.count] =
          i == kCm730Index ? BulkReadEntry{kCm730Id, kCm730ReadAddress, kCm730ReadLength}
                           : BulkReadEntry{device_id(i), kServoReadAddress, kServoReadLength};
      round.device[round.count++] = i;
    }
  }
}

void DynamixelRobot::exchange_bulk_read(BulkRound& round) noexcept {
  const std::size_t count = round.count;
  if (count == 0) return;
  const auto& entries = round.entries;
  std::size_t received = 0;
  const std::uint64_t bad_before = parser_.stats().bad_checksum;
  const std::size_t n = v1::encode_bulk_read(tx_, std::span(entries.data(), count));
  stream_->discard_input();
  parser_.reset();
  const std::uint32_t baud = stream_->baud();
  std::int64_t reply_wire = 0;
  for (std::size_t k = 0; k < count; ++k) reply_wire += wire_time_ns(6U + entries[k].length, baud);
  const std::int64_t budget_end =
      cycle_start_ns_ + static_cast<std::int64_t>(options_.bus_budget_fraction *
                                                  static_cast<double>(options_.period_ns));
  const std::int64_t t_send = monotonic_ns();
  std::int64_t deadline = t_send + wire_time_ns(n, baud) + reply_wire + options_.margin_ns;
  deadline = std::min(deadline, std::max(budget_end, t_send + wire_time_ns(n, baud)));
  if (!send(std::span(tx_.data(), n), deadline)) return;
  const std::int64_t t_rx = monotonic_ns();
  std::uint64_t seen_bad = bad_before;
  while (received < count) {
    while (parser_.next(packet_)) {
      for (std::size_t k = 0; k < count; ++k) {
        if (round.got[k] || entries[k].id != packet_.id) continue;
        const std::size_t i = round.device[k];
        if (packet_.param_count != entries[k].length) {
          round.corrupt[k] = true;
          break;
        }
        round.got[k] = true;
        ++received;
        DeviceDiagnostics& d = diagnostics_.devices[i];
        ++d.replies;
        d.last_error_flags = packet_.error;
        if (packet_.error != 0) ++d.error_replies;
        if (i == kCm730Index) {
          decode_cm730(packet_.params.data());
        } else {
          decode_servo(i, packet_.params.data());
        }
        break;
      }
    }
    while (seen_bad < parser_.stats().bad_checksum) {
      ++seen_bad;
      for (std::size_t k = 0; k < count; ++k) {
        if (entries[k].id == parser_.last_bad_id()) round.corrupt[k] = true;
      }
    }
    // Replies come in list order: once the last device has answered, a missing earlier
    // reply is lost for good, so there is nothing left to wait for.
    if (received == count || round.got[count - 1]) break;
    const std::ptrdiff_t r = stream_->read_some(rx_, deadline);
    if (r <= 0) {
      // Nothing more will come: a damaged length may hide complete packets behind it.
      if (parser_.skip_incomplete()) continue;
      break;
    }
    diagnostics_.bytes_rx += static_cast<std::uint64_t>(r);
    (void)parser_.feed(std::span<const std::uint8_t>(rx_.data(), static_cast<std::size_t>(r)));
  }
  diagnostics_.last_rx_ns = monotonic_ns() - t_rx;
  diagnostics_.max_rx_ns = std::max(diagnostics_.max_rx_ns, diagnostics_.last_rx_ns);
}

void DynamixelRobot::judge_bulk_read(const BulkRound& round) noexcept {
  bool blamed = false;
  for (std::size_t k = 0; k < round.count; ++k) {
    const std::size_t i = round.device[k];
    DeviceDiagnostics& d = diagnostics_.devices[i];
    if (round.got[k]) {
      d.consecutive_failures = 0;
      skipped_[i] = false;
      d.health = d.last_error_flags != 0 ? DeviceHealth::kError : DeviceHealth::kOk;
      continue;
    }
    if (round.corrupt[k]) {
      ++d.corrupt_replies;
    } else {
      ++d.timeouts;
    }
    d.health = skipped_[i] ? DeviceHealth::kMissing : DeviceHealth::kTimeout;
    if (!blamed) {
      // The reply chain stopped (or this reply was lost) here: blame this device and move it
      // to the end of the list so that the others answer next tick.
      blamed = true;
      ++d.consecutive_failures;
      if (d.consecutive_failures >= options_.max_consecutive_failures) {
        skipped_[i] = true;
        d.health = DeviceHealth::kMissing;
      }
      auto it = std::find(order_.begin(), order_.end(), static_cast<std::uint8_t>(i));
      if (it != order_.end()) std::rotate(it, it + 1, order_.end());
    }
  }
}

void DynamixelRobot::read(SensorFrame& out) noexcept {
  // The cycle's bus budget starts with its first transaction, the BULK_READ.
  cycle_start_ns_ = monotonic_ns();
  diagnostics_.last_tx_ns = 0;
  diagnostics_.last_rx_ns = 0;
  BulkRound round;
  plan_bulk_read(round);
  exchange_bulk_read(round);
  judge_bulk_read(round);
  for (std::size_t i = 0; i < kServoCount; ++i) {
    state_.servos[i].health = diagnostics_.devices[i].health;
    state_.servos[i].error_flags = diagnostics_.devices[i].last_error_flags;
  }
  state_.cm730.health = diagnostics_.devices[kCm730Index].health;
  state_.cm730.error_flags = diagnostics_.devices[kCm730Index].last_error_flags;
  state_.tick = tick_;
  out = state_;
}

void DynamixelRobot::write(const CommandFrame& commands) noexcept {
  std::array<std::uint8_t, kServoCount*(kSyncLength + 1)> records{};
  std::array<std::uint8_t, kServoCount * 3> gain_records{};
  std::array<std::uint8_t, kServoCount * 2> torque_records{};
  std::size_t used = 0;
  std::size_t gains_used = 0;
  std::size_t torque_used = 0;
  const Tick tick = commands.tick;
  for (std::size_t i = 0; i < kServoCount; ++i) {
    const ServoCommand& c = commands.servos[i];
    const ServoCalibration& cal = options_.calibration[i];
    const bool finite = std::isfinite(c.position_rad);
    // [P, reserved, goal L, goal H, speed L, speed H, torque limit L, torque limit H]
    std::array<std::uint8_t, kSyncLength> bytes = sent_bytes_[i];
    bytes[0] = units::gain_to_register(c.p_gain);
    bytes[1] = 0;
    if (finite || !sent_once_[i]) {
      const std::uint16_t goal =
          units::position_to_ticks(finite ? c.position_rad : state_.servos[i].position_rad, cal);
      bytes[2] = static_cast<std::uint8_t>(goal & 0xFFU);
      bytes[3] = static_cast<std::uint8_t>(goal >> 8);
    }
    const std::uint16_t speed = units::moving_speed_to_register(c.moving_speed_rad_s);
    bytes[4] = static_cast<std::uint8_t>(speed & 0xFFU);
    bytes[5] = static_cast<std::uint8_t>(speed >> 8);
    const std::uint16_t limit = units::torque_limit_to_register(c.torque_limit);
    bytes[6] = static_cast<std::uint8_t>(limit & 0xFFU);
    bytes[7] = static_cast<std::uint8_t>(limit >> 8);
    const bool refresh = options_.refresh_interval_ticks > 0 &&
                         tick - sent_tick_[i] >= static_cast<Tick>(options_.refresh_interval_ticks);
    if (!sent_once_[i] || bytes != sent_bytes_[i] || refresh) {
      records[used++] = device_id(i);
      for (const std::uint8_t b : bytes) records[used++] = b;
      sent_bytes_[i] = bytes;
      sent_tick_[i] = tick;
      sent_once_[i] = true;
    }
    const std::array<std::uint8_t, 2> gains{units::gain_to_register(c.d_gain),
                                            units::gain_to_register(c.i_gain)};
    if (!gains_sent_once_[i] || gains != gains_sent_[i]) {
      gain_records[gains_used++] = device_id(i);
      gain_records[gains_used++] = gains[0];
      gain_records[gains_used++] = gains[1];
      gains_sent_[i] = gains;
      gains_sent_once_[i] = true;
    }
    const std::int8_t torque = (c.torque_enable && finite) ? 1 : 0;
    if (torque != torque_sent_[i]) {
      torque_records[torque_used++] = device_id(i);
      torque_records[torque_used++] = static_cast<std::uint8_t>(torque);
      torque_sent_[i] = torque;
    }
    ServoState& s = state_.servos[i];
    s.goal_position_rad = units::ticks_to_position(read_u16(bytes.data() + 2), cal);
    s.p_gain = bytes[0];
    s.d_gain = gains_sent_[i][0];
    s.i_gain = gains_sent_[i][1];
    s.torque_limit = units::torque_limit_from_register(read_u16(bytes.data() + 6));
    s.torque_enabled = torque_sent_[i] == 1;
  }
  const std::uint32_t baud = stream_->baud();
  auto sync_write = [&](std::uint8_t address, std::uint8_t length, std::size_t count,
                        const std::uint8_t* data) {
    if (count == 0) return;
    const std::size_t n = v1::encode_sync_write(tx_, address, length, std::span(data, count));
    (void)send(std::span(tx_.data(), n),
               monotonic_ns() + wire_time_ns(n, baud) + options_.margin_ns);
  };
  sync_write(kGainAddress, 2, gains_used, gain_records.data());
  sync_write(kSyncAddress, kSyncLength, used, records.data());
  sync_write(mx1::kTorqueEnable, 1, torque_used, torque_records.data());
  diagnostics_.max_tx_ns = std::max(diagnostics_.max_tx_ns, diagnostics_.last_tx_ns);
  ++diagnostics_.cycles;
}

void DynamixelRobot::set_torque_enable(bool enabled) noexcept {
  const std::uint8_t value = enabled ? 1 : 0;
  const std::size_t n =
      v1::encode_write(tx_, kBroadcastId, mx1::kTorqueEnable, std::span(&value, 1));
  (void)send(std::span(tx_.data(), n),
             monotonic_ns() + wire_time_ns(n, stream_->baud()) + options_.margin_ns);
  torque_sent_.fill(static_cast<std::int8_t>(value));
  for (auto& s : state_.servos) s.torque_enabled = enabled;
}

std::string DynamixelRobot::health_report() const {
  std::string text;
  for (std::size_t i = 0; i < kDevices; ++i) {
    const DeviceDiagnostics& d = diagnostics_.devices[i];
    if (d.timeouts == 0 && d.corrupt_replies == 0 && d.error_replies == 0 &&
        d.health == DeviceHealth::kOk) {
      continue;
    }
    text += device_name(i) + ": " + std::to_string(d.replies) + " replies, " +
            std::to_string(d.timeouts) + " timeouts, " + std::to_string(d.corrupt_replies) +
            " corrupt, " + std::to_string(d.error_replies) + " with errors (last 0x" +
            (d.last_error_flags < 16 ? "0" : "") +
            [&] {
              static const char* hex = "0123456789abcdef";
              std::string h;
              if (d.last_error_flags >= 16) h += hex[d.last_error_flags >> 4];
              h += hex[d.last_error_flags & 0xF];
              return h;
            }() +
            "), health " +
            (d.health == DeviceHealth::kOk        ? "ok"
             : d.health == DeviceHealth::kError   ? "error"
             : d.health == DeviceHealth::kTimeout ? "timeout"
                                                  : "missing") +
            "\n";
  }
  return text;
}

Status open_dynamixel_robot(const std::string& port, std::uint32_t baud,
                            const DynamixelRobot::Options& options,
                            std::unique_ptr<DynamixelRobot>& out) {
  std::unique_ptr<SerialPort> serial;
  if (Status s = SerialPort::open(port, baud, serial); !s) return s;
  return DynamixelRobot::create(std::move(serial), options, out);
}

}  // namespace stride::hal::dxl
