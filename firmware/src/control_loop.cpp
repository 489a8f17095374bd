// ControlLoop implementation.
#include "stride/firmware/control_loop.hpp"

namespace stride::fw {

void ControlLoop::run_once() noexcept {
  const hal::Tick woke = robot_.sleep_until(next_);
  if (woke > next_) counters_.missed_ticks += static_cast<std::uint64_t>(woke - next_);
  robot_.read(sensors_);
  if (params_.apply_staged(recorder_)) ++counters_.param_batches;
  commands_ = controller_.step(sensors_, woke);
  robot_.write(commands_);
  if (recorder_ != nullptr) recorder_->on_tick(woke, sensors_, commands_);
  counters_.last_tick = woke;
  ++counters_.cycles;
  next_ = woke + 1;
}

void ControlLoop::run(std::int64_t cycles, const std::atomic<bool>* stop) noexcept {
  for (std::int64_t i = 0; cycles < 0 || i < cycles; ++i) {
    if (stop != nullptr && stop->load(std::memory_order_relaxed)) return;
    run_once();
  }
}

}  // namespace stride::fw
