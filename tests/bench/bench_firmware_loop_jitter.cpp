// Benchmark program: period jitter of the fixed-rate loop on the real clock.
// Runs the firmware on the scripted test HAL at loop.rate_hz (default 100 Hz) for --seconds
// (default 10), paced by RealtimeRobot (clock_nanosleep TIMER_ABSTIME on CLOCK_MONOTONIC),
// and prints wake-up jitter and compute time percentiles as JSON.
//
//   build/release/bench/bench_firmware_loop_jitter [--seconds 10] [--rate 100] [--no-rt]
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "stride/firmware/control_loop.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/firmware/realtime_robot.hpp"
#include "stride/hal/scripted_robot.hpp"

int main(int argc, char** argv) {
  double seconds = 10.0;
  double rate = 100.0;
  bool realtime = true;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) seconds = std::stod(argv[++i]);
    else if (std::strcmp(argv[i], "--rate") == 0 && i + 1 < argc) rate = std::stod(argv[++i]);
    else if (std::strcmp(argv[i], "--no-rt") == 0) realtime = false;
    else {
      std::fprintf(stderr, "usage: %s [--seconds S] [--rate HZ] [--no-rt]\n", argv[0]);
      return 2;
    }
  }
  std::unique_ptr<stride::fw::Firmware> firmware;
  if (stride::Status s = stride::fw::Firmware::create({}, firmware); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    return 1;
  }
  stride::hal::ScriptedRobot::Options options;
  options.period_ns = static_cast<std::int64_t>(1e9 / rate);
  options.echo_commands = true;
  options.record_capacity = 0;
  stride::hal::ScriptedRobot inner(options, {stride::hal::ScriptedRobot::standing_frame()});
  stride::fw::RealtimeRobot robot(inner);
  std::vector<std::string> warnings;
  if (realtime) warnings = robot.start({});
  for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

  stride::fw::ControlLoop loop(robot, firmware->controller(), firmware->params());
  loop.run(static_cast<std::int64_t>(seconds * rate));

  const auto us = [](std::int64_t ns) { return static_cast<double>(ns) / 1000.0; };
  nlohmann::json report = {
      {"rate_hz", rate},
      {"seconds", seconds},
      {"sched_fifo", realtime && warnings.empty()},
      {"cycles", loop.counters().cycles},
      {"skipped_ticks", robot.skipped_ticks()},
      {"jitter_us",
       {{"p50", us(robot.jitter().percentile(0.5))},
        {"p99", us(robot.jitter().percentile(0.99))},
        {"max", us(robot.jitter().max())}}},
      {"compute_us",
       {{"p50", us(robot.compute().percentile(0.5))},
        {"p99", us(robot.compute().percentile(0.99))},
        {"max", us(robot.compute().max())}}}};
  std::printf("%s\n", report.dump(2).c_str());
  return 0;
}
