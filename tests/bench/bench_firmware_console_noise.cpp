// Benchmark program: does the parameter console cost the control loop ticks?
//
// Runs the firmware loop on the scripted test HAL, paced by the real clock (RealtimeRobot,
// SCHED_FIFO when granted), twice for --seconds each:
//   1. baseline: the loop alone;
//   2. flooded: the console serves a pseudo-terminal while a flooder writes binary noise,
//      overlong lines and valid commands (set, status, flash) as fast as the pty takes them,
//      and closes and reopens the port every --reopen-ms.
// Prints, per phase, missed (skipped) ticks, wake-up jitter and compute time, and the console's
// counters, as JSON. Missed ticks attributable to the console = flooded - baseline.
//
//   build/release/bench/bench_firmware_console_noise [--seconds 10] [--rate 100] [--no-rt]
//                                                   [--reopen-ms 1000]
#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "stride/firmware/console/console_server.hpp"
#include "stride/firmware/control_loop.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/firmware/realtime_robot.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace {

using namespace std::chrono_literals;

struct Pty {
  int master = -1;
  std::string slave;
  bool open() {
    master = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (master < 0) master = ::open("/dev/pts/ptmx", O_RDWR | O_NOCTTY | O_CLOEXEC);
    char name[128];
    if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0 ||
        ptsname_r(master, name, sizeof name) != 0) {
      return false;
    }
    slave = name;
    termios raw{};
    if (tcgetattr(master, &raw) == 0) {
      cfmakeraw(&raw);
      (void)tcsetattr(master, TCSANOW, &raw);
    }
    (void)fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);
    return true;
  }
  void close() {
    if (master >= 0) ::close(master);
    master = -1;
  }
};

struct FloodStats {
  std::atomic<std::uint64_t> bytes_written{0};
  std::atomic<std::uint64_t> bytes_read{0};
  std::atomic<std::uint64_t> reopens{0};
};

// Writes noise, overlong lines and commands into the pty behind `link`, reading the replies,
// and replaces the pty every reopen_ms. Runs until `stop`.
void flood(const std::filesystem::path& link, int reopen_ms, const std::atomic<bool>& stop,
           FloodStats& stats) {
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> byte(0, 255);
  std::string noise(4096, '\0');
  const std::string overlong = std::string(70000, 'q') + "\r";
  const std::string commands =
      "\x03set stand.gain 40\rstatus\rset stand.gain 30\rget stand.gain\r"
      "flash {\"stand\":{\"gain\":35,\"ramp_time\":1.5}}\rlist\r";
  Pty pty;
  auto replace = [&] {
    pty.close();
    if (!pty.open()) return false;
    std::error_code ignored;
    std::filesystem::remove(link, ignored);
    std::filesystem::create_symlink(pty.slave, link, ignored);
    return true;
  };
  if (!replace()) return;
  auto next_reopen = std::chrono::steady_clock::now() + std::chrono::milliseconds(reopen_ms);
  char buffer[8192];
  std::uint64_t round = 0;
  while (!stop.load()) {
    if (std::chrono::steady_clock::now() >= next_reopen) {
      if (!replace()) return;
      ++stats.reopens;
      next_reopen += std::chrono::milliseconds(reopen_ms);
    }
    const std::string* chunk = &noise;
    if (round % 16 == 5) chunk = &overlong;
    if (round % 4 == 3) chunk = &commands;
    for (char& c : noise) c = static_cast<char>(byte(rng));
    ++round;
    std::size_t done = 0;
    while (done < chunk->size() && !stop.load()) {
      const ssize_t n = ::write(pty.master, chunk->data() + done, chunk->size() - done);
      if (n > 0) {
        done += static_cast<std::size_t>(n);
        stats.bytes_written += static_cast<std::uint64_t>(n);
      }
      const ssize_t r = ::read(pty.master, buffer, sizeof buffer);
      if (r > 0) stats.bytes_read += static_cast<std::uint64_t>(r);
      if (n <= 0) {
        pollfd p{pty.master, POLLOUT | POLLIN, 0};
        (void)::poll(&p, 1, 5);
        if (std::chrono::steady_clock::now() >= next_reopen) break;
      }
    }
  }
  pty.close();
}

nlohmann::json run_phase(bool flooded, double seconds, double rate, bool realtime, int reopen_ms) {
  std::unique_ptr<stride::fw::Firmware> firmware;
  if (stride::Status s = stride::fw::Firmware::create({}, firmware); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    std::exit(1);
  }
  stride::hal::ScriptedRobot::Options options;
  options.period_ns = static_cast<std::int64_t>(1e9 / rate);
  options.echo_commands = true;
  options.record_capacity = 0;
  stride::hal::ScriptedRobot inner(options, {stride::hal::ScriptedRobot::standing_frame()});
  stride::fw::RealtimeRobot robot(inner);
  stride::fw::ControlLoop loop(robot, firmware->controller(), firmware->params());

  // Helper threads first, so they do not inherit SCHED_FIFO from this thread.
  const auto link = std::filesystem::temp_directory_path() /
                    ("stride-bench-console-" + std::to_string(::getpid()));
  std::atomic<bool> stop{false};
  FloodStats stats;
  std::thread flooder;
  std::unique_ptr<stride::fw::console::ConsoleServer> console;
  if (flooded) {
    flooder = std::thread([&] { flood(link, reopen_ms, stop, stats); });
    std::this_thread::sleep_for(50ms);
    stride::fw::console::ConsoleContext context;
    context.params = &firmware->params();
    context.controller = &firmware->controller();
    context.servos = &firmware->servos();
    context.default_file = link.string() + ".json";
    console = stride::fw::console::make_console(link.string(), context);
    console->start();
  }
  std::vector<std::string> warnings;
  if (realtime) warnings = robot.start({});
  for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

  loop.run(static_cast<std::int64_t>(seconds * rate));

  // Back to normal priority before joining the helpers.
  sched_param normal{};
  (void)sched_setscheduler(0, SCHED_OTHER, &normal);
  nlohmann::json console_json = nullptr;
  if (flooded) {
    stop = true;
    flooder.join();
    console->stop();
    const auto& c = console->counters();
    console_json = {{"bytes_flooded", stats.bytes_written.load()},
                    {"bytes_replied", stats.bytes_read.load()},
                    {"port_replaced", stats.reopens.load()},
                    {"lines", c.lines.load()},
                    {"error_replies", c.errors.load()},
                    {"overlong_lines", c.overlong_lines.load()},
                    {"noise_bytes_dropped", c.noise_bytes.load()},
                    {"opens", c.opens.load()},
                    {"link_losses", c.link_losses.load()},
                    {"failed_opens", c.failed_opens.load()}};
    std::error_code ignored;
    std::filesystem::remove(link, ignored);
    std::filesystem::remove(link.string() + ".json", ignored);
  }
  const auto us = [](std::int64_t ns) { return static_cast<double>(ns) / 1000.0; };
  return {{"phase", flooded ? "console flooded" : "baseline"},
          {"sched_fifo", realtime && warnings.empty()},
          {"cycles", loop.counters().cycles},
          {"missed_ticks", robot.skipped_ticks() + loop.counters().missed_ticks},
          {"param_batches", loop.counters().param_batches},
          {"jitter_us",
           {{"p50", us(robot.jitter().percentile(0.5))},
            {"p99", us(robot.jitter().percentile(0.99))},
            {"max", us(robot.jitter().max())}}},
          {"compute_us",
           {{"p50", us(robot.compute().percentile(0.5))},
            {"p99", us(robot.compute().percentile(0.99))},
            {"max", us(robot.compute().max())}}},
          {"console", console_json}};
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 10.0;
  double rate = 100.0;
  bool realtime = true;
  int reopen_ms = 1000;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) {
      seconds = std::stod(argv[++i]);
    } else if (std::strcmp(argv[i], "--rate") == 0 && i + 1 < argc) {
      rate = std::stod(argv[++i]);
    } else if (std::strcmp(argv[i], "--reopen-ms") == 0 && i + 1 < argc) {
      reopen_ms = std::stoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--no-rt") == 0) {
      realtime = false;
    } else {
      std::fprintf(stderr, "usage: %s [--seconds S] [--rate HZ] [--no-rt] [--reopen-ms MS]\n",
                   argv[0]);
      return 2;
    }
  }
  const nlohmann::json baseline = run_phase(false, seconds, rate, realtime, reopen_ms);
  const nlohmann::json flooded = run_phase(true, seconds, rate, realtime, reopen_ms);
  const nlohmann::json report = {
      {"rate_hz", rate},
      {"seconds_per_phase", seconds},
      {"baseline", baseline},
      {"flooded", flooded},
      {"missed_ticks_attributable_to_console",
       flooded["missed_ticks"].get<std::int64_t>() - baseline["missed_ticks"].get<std::int64_t>()}};
  std::printf("%s\n", report.dump(2).c_str());
  return 0;
}
