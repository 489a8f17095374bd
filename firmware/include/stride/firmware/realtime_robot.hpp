// RealtimeRobot: paces any Robot by the real clock. It forwards read/write to the wrapped
// robot and implements sleep_until(tick) as clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME)
// to t0 + tick * period, where t0 is the time of the first sleep_until call.
//
// If the caller is late by a whole period or more, the missed ticks are skipped (the returned
// tick is the latest one whose time has come), never caught up. It measures:
//   - wake-up jitter: how late each wake-up was relative to its tick time;
//   - compute time: from a wake-up to the next sleep_until call (read + step + write).
// start() asks for SCHED_FIFO and locks memory (mlockall); where the OS refuses, it carries on
// and returns the warnings for the caller to print.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "stride/firmware/latency_histogram.hpp"
#include "stride/hal/robot.hpp"

namespace stride::fw {

struct RealtimeOptions {
  bool lock_memory = true;
  bool sched_fifo = true;
  int priority = 80;  ///< SCHED_FIFO priority 1..99
};

class RealtimeRobot final : public hal::Robot {
 public:
  explicit RealtimeRobot(hal::Robot& inner) : inner_(inner) {}

  /// Requests real-time scheduling and locked memory for the calling thread. Returns one
  /// warning per request the OS refused (empty when all were granted). Not real-time.
  std::vector<std::string> start(const RealtimeOptions& options);

  std::int64_t period_ns() const noexcept override { return inner_.period_ns(); }
  hal::Tick sleep_until(hal::Tick tick) noexcept override;
  void read(hal::SensorFrame& out) noexcept override { inner_.read(out); }
  void write(const hal::CommandFrame& commands) noexcept override { inner_.write(commands); }
  void set_torque_enable(bool enabled) noexcept override { inner_.set_torque_enable(enabled); }
  const hal::Diagnostics& diagnostics() const noexcept override { return inner_.diagnostics(); }

  const LatencyHistogram& jitter() const noexcept { return jitter_; }
  const LatencyHistogram& compute() const noexcept { return compute_; }
  std::uint64_t skipped_ticks() const noexcept { return skipped_; }

 private:
  hal::Robot& inner_;
  std::int64_t t0_ns_ = 0;
  std::int64_t last_wake_ns_ = 0;
  bool started_clock_ = false;
  std::uint64_t skipped_ = 0;
  LatencyHistogram jitter_;
  LatencyHistogram compute_;
};

/// CLOCK_MONOTONIC now [ns]. Not for controller code (the controller reads no clock).
std::int64_t monotonic_now_ns() noexcept;

}  // namespace stride::fw
