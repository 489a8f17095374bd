// LatencyHistogram and RealtimeRobot's overrun handling.
#include <sys/stat.h>

#include <chrono>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "stride/firmware/latency_histogram.hpp"
#include "stride/firmware/realtime_robot.hpp"
#include "stride/hal/scripted_robot.hpp"
#include "temp_dir.hpp"

namespace stride::fw {
namespace {

TEST(LatencyHistogram, PercentilesAtMicrosecondResolution) {
  LatencyHistogram h;
  for (int i = 1; i <= 100; ++i) h.add(i * 1000 - 500);  // 0.5 us .. 99.5 us
  EXPECT_EQ(h.count(), 100u);
  EXPECT_EQ(h.percentile(0.5), 50'000);
  EXPECT_EQ(h.percentile(0.99), 99'000);
  EXPECT_EQ(h.max(), 99'500);
  h.add(50'000'000);  // 50 ms lands in a coarse bucket
  EXPECT_EQ(h.max(), 50'000'000);
  EXPECT_GE(h.percentile(1.0), 50'000'000);
  h.clear();
  EXPECT_EQ(h.percentile(0.5), 0);
}

TEST(RealtimeRobot, SkipsWholeMissedPeriodsInsteadOfCatchingUp) {
  hal::ScriptedRobot::Options options;
  options.period_ns = 10'000'000;  // 10 ms
  hal::ScriptedRobot inner(options, {hal::ScriptedRobot::standing_frame()});
  RealtimeRobot robot(inner);
  EXPECT_EQ(robot.sleep_until(0), 0);
  // Overrun: 35 ms of work before asking for tick 1 (due at 10 ms) makes ticks 1 and 2 late
  // by at least a whole period.
  std::this_thread::sleep_for(std::chrono::milliseconds(35));
  const hal::Tick woke = robot.sleep_until(1);
  EXPECT_GE(woke, 3);
  EXPECT_EQ(robot.skipped_ticks(), static_cast<std::uint64_t>(woke - 1));
  // On time again: the next tick is waited for, not skipped.
  EXPECT_EQ(robot.sleep_until(woke + 1), woke + 1);
  EXPECT_EQ(robot.skipped_ticks(), static_cast<std::uint64_t>(woke - 1));
  EXPECT_EQ(robot.jitter().count(), 3u);
  EXPECT_EQ(robot.compute().count(), 2u);
}

}  // namespace
}  // namespace stride::fw
