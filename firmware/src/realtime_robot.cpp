// RealtimeRobot implementation (POSIX clocks and scheduling).
#include "stride/firmware/realtime_robot.hpp"

#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <cerrno>
#include <cstring>

namespace stride::fw {

std::int64_t monotonic_now_ns() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::vector<std::string> RealtimeRobot::start(const RealtimeOptions& options) {
  std::vector<std::string> warnings;
  if (options.lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    warnings.push_back(std::string("mlockall refused (") + std::strerror(errno) +
                       "): page faults may add latency");
  }
  if (options.sched_fifo) {
    sched_param param{};
    param.sched_priority = options.priority;
    if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
      warnings.push_back(std::string("SCHED_FIFO refused (") + std::strerror(errno) +
                         "): running with normal priority");
    }
  }
  return warnings;
}

hal::Tick RealtimeRobot::sleep_until(hal::Tick tick) noexcept {
  hal::Tick target_tick = inner_.sleep_until(tick);  // e.g. the simulation advances here
  const std::int64_t period = inner_.period_ns();
  std::int64_t now = monotonic_now_ns();
  if (!started_clock_) {
    started_clock_ = true;
    t0_ns_ = now - target_tick * period;
  } else {
    compute_.add(now - last_wake_ns_);
  }
  std::int64_t target = t0_ns_ + target_tick * period;
  if (now - target >= period) {  // overran by whole periods: skip to the latest due tick
    const hal::Tick behind = (now - target) / period;
    skipped_ += static_cast<std::uint64_t>(behind);
    target_tick += behind;
    target += behind * period;
  }
  if (now < target) {
    timespec ts{};
    ts.tv_sec = target / 1'000'000'000;
    ts.tv_nsec = target % 1'000'000'000;
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
    now = monotonic_now_ns();
  }
  jitter_.add(now - target);
  last_wake_ns_ = now;
  return target_tick;
}

}  // namespace stride::fw
