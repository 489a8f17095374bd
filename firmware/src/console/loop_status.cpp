// Loop statistics lines for the console's `status` command.
#include "stride/firmware/console/loop_status.hpp"

#include <cstdio>

namespace stride::fw::console {

std::function<std::vector<std::string>()> loop_status_lines(const ControlLoop& loop,
                                                            const RealtimeRobot* paced,
                                                            const hal::Robot& robot) {
  return [&loop, paced, &robot] {
    std::vector<std::string> lines;
    char text[256];
    const LoopCounters& c = loop.counters();
    const unsigned long long skipped = paced != nullptr ? paced->skipped_ticks() : 0;
    std::snprintf(text, sizeof text, "loop: cycles %llu  missed ticks %llu  param batches %llu",
                  static_cast<unsigned long long>(c.cycles),
                  static_cast<unsigned long long>(c.missed_ticks) + skipped,
                  static_cast<unsigned long long>(c.param_batches));
    lines.emplace_back(text);
    if (paced != nullptr) {
      const auto& j = paced->jitter();
      const auto& k = paced->compute();
      std::snprintf(text, sizeof text,
                    "timing: jitter p50 %.1f p99 %.1f max %.1f us  compute p50 %.1f p99 %.1f "
                    "max %.1f us",
                    j.percentile(0.5) / 1e3, j.percentile(0.99) / 1e3, j.max() / 1e3,
                    k.percentile(0.5) / 1e3, k.percentile(0.99) / 1e3, k.max() / 1e3);
      lines.emplace_back(text);
    }
    const hal::Diagnostics& d = robot.diagnostics();
    unsigned long long timeouts = 0, corrupt = 0, error_replies = 0, replies = 0;
    for (const auto& device : d.devices) {
      timeouts += device.timeouts;
      corrupt += device.corrupt_replies;
      error_replies += device.error_replies;
      replies += device.replies;
    }
    std::snprintf(text, sizeof text,
                  "bus: replies %llu  timeouts %llu  corrupt %llu  error replies %llu  tx %.1f us  "
                  "rx %.1f us (max %.1f / %.1f)",
                  replies, timeouts, corrupt, error_replies,
                  static_cast<double>(d.last_tx_ns) / 1e3, static_cast<double>(d.last_rx_ns) / 1e3,
                  static_cast<double>(d.max_tx_ns) / 1e3, static_cast<double>(d.max_rx_ns) / 1e3);
    lines.emplace_back(text);
    return lines;
  };
}

}  // namespace stride::fw::console
