// LatencyHistogram, CliArgs, atomic file writes and RealtimeRobot's overrun handling.
#include <sys/stat.h>

#include <chrono>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "stride/firmware/atomic_file.hpp"
#include "stride/firmware/cli_args.hpp"
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

TEST(CliArgs, ParsesOptionsFlagsAndPositionals) {
  CliArgs args;
  args.option("port", "device").option("json", "json", false).option("rate", "hz", true, "100");
  const char* argv[] = {"x", "scan", "--port", "/dev/ttyUSB0", "--json", "--rate=90", "extra"};
  ASSERT_TRUE(args.parse(7, argv));
  EXPECT_EQ(args.get("port"), "/dev/ttyUSB0");
  EXPECT_TRUE(args.has("json"));
  std::int64_t rate = 0;
  ASSERT_TRUE(args.get_int("rate", rate));
  EXPECT_EQ(rate, 90);
  EXPECT_EQ(args.positional(), (std::vector<std::string>{"scan", "extra"}));
}

TEST(CliArgs, ARepeatedOptionKeepsEveryValueInOrder) {
  CliArgs args;
  args.option("push", "repeatable").option("seed", "one value", true, "1");
  const char* argv[] = {"x", "--push", "1,left,1", "--push=2,right,0.5", "--seed", "3"};
  ASSERT_TRUE(args.parse(6, argv));
  EXPECT_EQ(args.get_all("push"), (std::vector<std::string>{"1,left,1", "2,right,0.5"}));
  EXPECT_EQ(args.get("push"), "2,right,0.5");  // get() is the last
  EXPECT_TRUE(args.get_all("seed") == std::vector<std::string>{"3"});
  CliArgs defaults;
  defaults.option("seed", "one value", true, "1");
  const char* none[] = {"x"};
  ASSERT_TRUE(defaults.parse(1, none));
  EXPECT_TRUE(defaults.get_all("seed").empty());  // a default is not a value given
}

TEST(CliArgs, BadInputIsNamed) {
  CliArgs args;
  args.option("port", "device").option("json", "json", false).option("vx", "speed");
  const char* unknown[] = {"x", "--prot", "a"};
  Status s = args.parse(3, unknown);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("--prot"), std::string::npos);
  CliArgs a2 = args;
  const char* missing[] = {"x", "--port"};
  EXPECT_FALSE(a2.parse(2, missing));
  CliArgs a3 = args;
  const char* flag_value[] = {"x", "--json=1"};
  EXPECT_FALSE(a3.parse(2, flag_value));
  CliArgs a4 = args;
  const char* bad_number[] = {"x", "--vx", "fast"};
  ASSERT_TRUE(a4.parse(3, bad_number));
  double vx = 0;
  s = a4.get_double("vx", vx);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("--vx"), std::string::npos);
}

TEST(AtomicFile, ReplacesContentsAndLeavesNoTemporaries) {
  test::TempDir dir;
  const auto path = dir.path() / "out.json";
  ASSERT_TRUE(write_file_atomically(path, "first"));
  ASSERT_TRUE(write_file_atomically(path, "second"));
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text, "second");
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(AtomicFile, FailureNamesTheFileAndKeepsTheOldContents) {
  test::TempDir dir;
  const auto path = dir.path() / "keep.txt";
  ASSERT_TRUE(write_file_atomically(path, "old"));
  const Status s = write_file_atomically(dir.path() / "missing-dir" / "x.txt", "new");
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("missing-dir"), std::string::npos);
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text, "old");
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
