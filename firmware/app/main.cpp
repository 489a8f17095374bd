// stride-fw: the robot binary. Builds the firmware, picks a HAL backend, runs the fixed-rate
// loop until --ticks have run or SIGINT/SIGTERM, then prints the loop statistics.
#include <atomic>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "stride/firmware/console/console_server.hpp"
#include "stride/firmware/console/loop_status.hpp"
#include "stride/firmware/control_loop.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/firmware/hal_registry.hpp"
#include "stride/firmware/realtime_robot.hpp"
#include "stride/firmware/recorder/flight_recorder.hpp"

using namespace stride;

namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) {
  g_stop.store(true);
}

int fail(int code, const std::string& message) {
  std::fprintf(stderr, "stride-fw: %s\n", message.c_str());
  return code;
}

double us(std::int64_t ns) {
  return static_cast<double>(ns) / 1000.0;
}

/// "test|dynamixel|...": the HAL backends by name.
std::string backend_names() {
  std::string names;
  for (const auto& b : fw::hal_backends())
    names += (names.empty() ? "" : "|") + std::string(b.name);
  return names;
}

/// stride-fw's options, and each backend's own.
void declare_options(core::CliArgs& args) {
  args.option("hal", "HAL backend: " + backend_names(), true, "test")
      .option("params", "parameter file (JSON) applied at start-up")
      .option("servo-table", "servo table file", true, fw::ServoTable::default_path().string())
      .option("robot-description",
              "rigid-body model from `stride describe` (must match the "
              "servo table)",
              true, fw::RobotDescription::default_path().string())
      .option("console", "serve the parameter console on DEV (serial device or pty) or stdio")
      .option("ticks", "stop after N ticks (default: run until SIGINT)")
      .option("record", "flight recorder: write every tick to LOG (format: FLIGHT_LOG.md)")
      .option("record-buffer-kb", "flight recorder's ring buffer [KiB]; a full one drops ticks",
              true, "4096")
      .option("no-rt", "do not ask for SCHED_FIFO and mlockall", false)
      .option("json", "print the final report as one JSON object on stdout", false)
      .option("help", "show this help", false);
  for (const auto& b : fw::hal_backends()) b.declare_options(args);
}

void print_help(const core::CliArgs& args) {
  std::printf("usage: stride-fw --hal NAME [options]\n\nbackends:\n");
  for (const auto& b : fw::hal_backends()) {
    std::printf("  %-8.*s %.*s\n", static_cast<int>(b.name.size()), b.name.data(),
                static_cast<int>(b.help.size()), b.help.data());
  }
  std::printf("\n%s", args.help().c_str());
}

/// --ticks, --record-buffer-kb and the backend of --hal, checked.
Status read_run_options(const core::CliArgs& args, std::int64_t& ticks, std::int64_t& buffer_kb,
                        const fw::HalBackend*& backend) {
  if (Status s = args.get_int("ticks", ticks); !s) return s;
  if (Status s = args.get_int("record-buffer-kb", buffer_kb); !s) return s;
  if (buffer_kb < 4 || buffer_kb > (1 << 22))
    return Status::error("--record-buffer-kb: must be in [4, 4194304], got " +
                         std::to_string(buffer_kb));
  for (const auto& b : fw::hal_backends()) {
    if (b.name == args.get("hal")) backend = &b;
  }
  if (backend == nullptr)
    return Status::error("unknown --hal '" + args.get("hal") + "' (available: " + backend_names() +
                         ")");
  return Status::ok();
}

/// The flight recorder of --record (null without it), opened before the HAL so that a bad path
/// fails before a port opens.
Status open_recorder(const core::CliArgs& args, std::int64_t buffer_kb,
                     const fw::FirmwareOptions& options, std::string_view hal,
                     fw::Firmware& firmware, std::unique_ptr<fw::FlightRecorder>& out) {
  if (!args.has("record")) return Status::ok();
  fw::RecorderOptions record;
  record.path = args.get("record");
  record.buffer_bytes = static_cast<std::size_t>(buffer_kb) * 1024;
  fw::flight_log::HeaderInputs header;
  header.params = &firmware.params();
  header.servos = &firmware.servos();
  header.servo_table_file = options.servo_table;
  header.robot = &firmware.robot();
  header.robot_description_file = options.robot_description;
  header.period_ns = firmware.period_ns();
  header.hal = std::string(hal);
  header.params_file = options.params_file.value_or("");
  if (Status s = fw::FlightRecorder::open(record, header, firmware.controller(), out); !s)
    return Status::error("--record: " + s.message());
  return Status::ok();
}

/// The parameter console on `device`, serving the firmware's parameters and the loop's status.
std::unique_ptr<fw::console::ConsoleServer> start_console(
    const std::string& device, fw::Firmware& firmware, const fw::FirmwareOptions& options,
    const fw::ControlLoop& loop, const fw::RealtimeRobot* paced, hal::Robot& robot) {
  fw::console::ConsoleContext context;
  context.params = &firmware.params();
  context.controller = &firmware.controller();
  context.servos = &firmware.servos();
  if (options.params_file) context.default_file = *options.params_file;
  context.loop_status = fw::console::loop_status_lines(loop, paced, robot);
  auto console = fw::console::make_console(device, std::move(context));
  console->start();
  return console;
}

/// The run's figures: loop counters, motion state, jitter and compute time (when paced by the
/// clock), bus timings, the backend's own and the recorder's totals.
nlohmann::json loop_report(std::string_view hal, double rate_hz, const fw::ControlLoop& loop,
                           fw::Firmware& firmware, const fw::RealtimeRobot* paced,
                           const hal::Robot& robot, const fw::HalInstance& instance,
                           const fw::RecorderTotals* recorded, const std::string& record_path) {
  const auto& c = loop.counters();
  const auto status = firmware.controller().status();
  nlohmann::json report = {{"hal", std::string(hal)},
                           {"rate_hz", rate_hz},
                           {"cycles", c.cycles},
                           {"missed_ticks", c.missed_ticks},
                           {"param_batches", c.param_batches},
                           {"motion_state", std::string(fw::to_string(status.state))},
                           {"fallen", status.safety.fallen}};
  if (paced != nullptr) {
    const auto& j = paced->jitter();
    const auto& k = paced->compute();
    report["jitter_us"] = {
        {"p50", us(j.percentile(0.5))}, {"p99", us(j.percentile(0.99))}, {"max", us(j.max())}};
    report["compute_us"] = {
        {"p50", us(k.percentile(0.5))}, {"p99", us(k.percentile(0.99))}, {"max", us(k.max())}};
  }
  const auto& d = robot.diagnostics();
  report["bus"] = {{"last_tx_us", us(d.last_tx_ns)},
                   {"last_rx_us", us(d.last_rx_ns)},
                   {"max_tx_us", us(d.max_tx_ns)},
                   {"max_rx_us", us(d.max_rx_ns)}};
  if (instance.report) instance.report(report);
  if (recorded != nullptr) {
    report["record"] = {{"path", record_path},
                        {"ticks_recorded", recorded->ticks_recorded},
                        {"ticks_dropped", recorded->ticks_dropped},
                        {"bytes", recorded->bytes_written},
                        {"write_error", recorded->write_error}};
  }
  return report;
}

/// loop_report as the lines a person reads.
void print_report(const nlohmann::json& report) {
  std::printf("loop: %llu cycles at %.0f Hz, %llu missed ticks, motion %s\n",
              static_cast<unsigned long long>(report["cycles"].get<std::uint64_t>()),
              report["rate_hz"].get<double>(),
              static_cast<unsigned long long>(report["missed_ticks"].get<std::uint64_t>()),
              report["motion_state"].get<std::string>().c_str());
  if (report.contains("jitter_us")) {
    std::printf("period jitter: p50 %.1f us, p99 %.1f us, max %.1f us\n",
                report["jitter_us"]["p50"].get<double>(), report["jitter_us"]["p99"].get<double>(),
                report["jitter_us"]["max"].get<double>());
    std::printf("compute time:  p50 %.1f us, p99 %.1f us, max %.1f us\n",
                report["compute_us"]["p50"].get<double>(),
                report["compute_us"]["p99"].get<double>(),
                report["compute_us"]["max"].get<double>());
  }
  std::printf("bus: last tx %.1f us, last rx %.1f us\n", report["bus"]["last_tx_us"].get<double>(),
              report["bus"]["last_rx_us"].get<double>());
  if (report.contains("record")) {
    const nlohmann::json& r = report["record"];
    std::printf("record: %llu ticks, %llu dropped, %llu bytes in %s\n",
                static_cast<unsigned long long>(r["ticks_recorded"].get<std::uint64_t>()),
                static_cast<unsigned long long>(r["ticks_dropped"].get<std::uint64_t>()),
                static_cast<unsigned long long>(r["bytes"].get<std::uint64_t>()),
                r["path"].get<std::string>().c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  core::CliArgs args;
  declare_options(args);
  if (Status s = args.parse(argc, argv); !s) return fail(2, s.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  std::int64_t ticks = -1, record_buffer_kb = 0;
  const fw::HalBackend* backend = nullptr;
  if (Status s = read_run_options(args, ticks, record_buffer_kb, backend); !s)
    return fail(2, s.message());

  fw::FirmwareOptions options;
  options.servo_table = args.get("servo-table");
  options.robot_description = args.get("robot-description");
  if (args.has("params")) {
    options.params_file = args.get("params");
  } else if (backend->default_params != nullptr) {
    // A backend's world with a walk of its own (the simulator's --world seed).
    if (const std::string file = backend->default_params(args); !file.empty())
      options.params_file = file;
  }
  std::unique_ptr<fw::Firmware> firmware;
  if (Status s = fw::Firmware::create(options, firmware); !s) return fail(2, s.message());
  if (backend->check_options != nullptr)
    if (Status s = backend->check_options(args, firmware->period_ns()); !s)
      return fail(2, s.message());

  std::unique_ptr<fw::FlightRecorder> recorder;
  if (Status s = open_recorder(args, record_buffer_kb, options, backend->name, *firmware, recorder);
      !s)
    return fail(2, s.message());

  fw::HalInstance instance;
  if (Status s = backend->make(args, firmware->period_ns(), instance); !s) {
    if (recorder) {
      (void)recorder->close();
      std::error_code ignored;
      std::filesystem::remove(args.get("record"), ignored);  // no log of a run that never ran
    }
    return fail(1, s.message());
  }
  hal::Robot* robot = instance.robot.get();
  std::unique_ptr<fw::RealtimeRobot> paced;
  if (instance.paced_by_clock) {
    paced = std::make_unique<fw::RealtimeRobot>(*instance.robot);
    if (!args.has("no-rt")) {
      for (const auto& warning : paced->start({})) {
        std::fprintf(stderr, "stride-fw: warning: %s\n", warning.c_str());
      }
    }
    robot = paced.get();
  }

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const double rate_hz = 1e9 / static_cast<double>(firmware->period_ns());
  std::fprintf(stderr, "stride-fw: hal=%s rate=%.0f Hz %s\n", std::string(backend->name).c_str(),
               rate_hz, ticks >= 0 ? ("ticks=" + std::to_string(ticks)).c_str() : "(Ctrl-C stops)");

  fw::ControlLoop loop(*robot, firmware->controller(), firmware->params());
  loop.set_recorder(recorder.get());
  std::unique_ptr<fw::console::ConsoleServer> console;
  if (args.has("console"))
    console = start_console(args.get("console"), *firmware, options, loop, paced.get(), *robot);
  loop.run(ticks, &g_stop);
  if (console) console->stop();
  fw::RecorderTotals recorded;
  if (recorder) recorded = recorder->close();

  const nlohmann::json report =
      loop_report(backend->name, rate_hz, loop, *firmware, paced.get(), *robot, instance,
                  recorder ? &recorded : nullptr, args.get("record"));
  if (recorder && !recorded.write_error.empty()) {
    std::fprintf(stderr,
                 "stride-fw: warning: --record: writing %s failed (%s); the log ends "
                 "at the failure\n",
                 args.get("record").c_str(), recorded.write_error.c_str());
  }
  if (args.has("json")) {
    std::printf("%s\n", report.dump().c_str());
  } else {
    print_report(report);
  }
  return 0;
}
