// `stride vbus --link PATH`: the virtual robot bus (20 MX servos + CM730, protocol 1.0; or 20
// MX(2.0) servos, protocol 2.0) on a pseudo-terminal, with injectable faults, until
// SIGINT/SIGTERM; `--json` prints the bus counters on exit.
#include <sched.h>
#include <sys/mman.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/cli_args.hpp"
#include "stride/firmware/dynamixel_config.hpp"
#include "stride/hal/dynamixel/pty_bus_server.hpp"
#include "stride/hal/dynamixel/virtual_bus.hpp"
#include "stride/hal/dynamixel/virtual_bus_v2.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_bus_physics.hpp"
#include "stride/sim_hal/sim_cli.hpp"

namespace {

std::atomic<bool> g_vbus_stop{false};

void on_vbus_signal(int) {
  g_vbus_stop.store(true);
}

const stride::tools::CommandErrors errors("vbus");

using stride::Status;
namespace dxl = stride::hal::dxl;
namespace fw = stride::fw;
namespace sim = stride::sim;

/// --fault may repeat (and take comma-separated items): it is taken out of argv before CliArgs
/// sees the rest.
Status split_faults(int argc, char** argv, std::vector<std::string>& faults,
                    std::vector<const char*>& rest) {
  for (int i = 0; i < argc; ++i) {
    const std::string word = argv[i];
    std::string value;
    if (word == "--fault") {
      if (i + 1 >= argc) return Status::error("option --fault needs a value");
      value = argv[++i];
    } else if (word.rfind("--fault=", 0) == 0) {
      value = word.substr(8);
    } else {
      rest.push_back(argv[i]);
      continue;
    }
    std::size_t start = 0;
    while (start <= value.size()) {
      const auto comma = value.find(',', start);
      faults.push_back(
          value.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  return {};
}

void declare_options(stride::core::CliArgs& args) {
  args.option("link", "path of the symlink to create to the pseudo-terminal (required)")
      .option(
          "fault",
          "inject a fault (repeatable, or comma-separated): drop:P, corrupt:P (per reply), "
          "silent:ID, overheat:ID, start:CYCLES (faults act after that many BULK_READs, or with "
          "--protocol 2 SYNC_READs and BULK_READs), seed:N")
      .option("protocol",
              "1: CM730 + 20 MX servos (the robot's bus); 2: 20 MX(2.0) servos, no CM730", true,
              "1")
      .option("lockstep",
              "advance the servo model one period per BULK_READ (deterministic); "
              "default: by wall-clock time",
              false)
      .option("period-ms", "control period for --lockstep [ms]", true, "10")
      .option("servo-table", "servo table file", true, fw::ServoTable::default_path().string())
      .option("no-rt",
              "do not ask for SCHED_FIFO and mlockall (asked for by default, so that "
              "replies are not late on a busy machine)",
              false)
      .option("cm730",
              "the CM730's firmware to serve: stock (ROBOTIS table) or nimbro (NimbRo's: 16-bit "
              "IMU and a magnetometer); default: nimbro when --imu is cm730-nimbro, else stock",
              true)
      .option("sim",
              "back the servos and the IMU with the Simbody simulation of the robot "
              "(protocol 1; implies --lockstep: one control period per BULK_READ)",
              false)
      .option("json", "print the bus counters as one JSON object on exit", false)
      .option("help", "show this help", false);
  sim::declare_world_options(args);
}

void print_help(const stride::core::CliArgs& args) {
  std::printf(
      "usage: stride vbus --link PATH [--fault KIND:VALUE]... [--lockstep] [--json]\n\n"
      "Serves an emulated CM730 (ID 200) and 20 MX-64/MX-106 servos (IDs 1-20, models from\n"
      "the servo table) with their protocol 1.0 control tables on a pseudo-terminal until\n"
      "SIGINT/SIGTERM (--protocol 2: 20 MX(2.0) servos, no CM730). Servo motion:\n"
      "first-order model, or with --sim the Simbody simulation of the robot, advanced one\n"
      "period per BULK_READ.\n\n%s",
      args.help().c_str());
}

/// The bus options from the command line; `protocol` 1 or 2, `sim`: back it with the simulation
/// (and `world` its world). Errors are bad input.
Status read_bus_options(const stride::core::CliArgs& args, const std::vector<std::string>& faults,
                        dxl::VirtualBus::Options& options, std::int64_t& protocol, bool& use_sim,
                        sim::WorldOptions& world) {
  if (!args.has("link")) return Status::error("missing --link PATH");
  for (const auto& f : faults) {
    if (Status s = options.faults.add(f); !s) return s;
  }
  double period_ms = 10.0;
  if (Status s = args.get_double("period-ms", period_ms); !s) return s;
  if (!(period_ms > 0.0 && period_ms <= 1000.0))
    return Status::error("option --period-ms: must be in (0, 1000]");
  if (Status s = args.get_int("protocol", protocol); !s) return s;
  if (protocol != 1 && protocol != 2) return Status::error("option --protocol: must be 1 or 2");
  fw::ServoTable table;
  if (Status s = fw::ServoTable::load(args.get("servo-table"), table); !s) return s;
  options.calibration = fw::servo_calibrations(table);
  use_sim = args.has("sim");
  if (use_sim && protocol != 1)
    return Status::error("option --sim: needs --protocol 1 (the CM730's IMU)");
  options.lockstep = args.has("lockstep") || use_sim;
  options.period_ns = static_cast<std::int64_t>(period_ms * 1e6);
  const bool profile_given = args.has("cm730");
  if (profile_given && !dxl::parse_cm730_profile(args.get("cm730"), options.cm730_profile))
    return Status::error("option --cm730: expected stock or nimbro, got '" + args.get("cm730") +
                         "'");
  if (use_sim) {
    if (Status s = sim::read_world_options(args, world); !s) return s;
    world.control_period_ns = options.period_ns;
    // The CM730 serves what its chips read: NimbRo's table goes with NimbRo's IMU chain.
    const bool nimbro_imu = world.imu_kind() == sim::ImuKind::kCm730Nimbro;
    if (!profile_given && nimbro_imu) options.cm730_profile = dxl::Cm730Profile::kNimbro;
    if (options.cm730_profile == dxl::Cm730Profile::kNimbro && !nimbro_imu) {
      if (args.has("imu"))
        return Status::error(
            "option --cm730 nimbro: the simulation's --imu must be cm730-nimbro, got '" +
            args.get("imu") + "'");
      world.use_imu(sim::ImuKind::kCm730Nimbro);
    }
  }
  return {};
}

/// The emulated bus: protocol 1.0 (CM730 + servos, first-order servo model or the simulation)
/// or 2.0 (servos only).
struct Bus {
  std::unique_ptr<dxl::BusResponder> responder;
  dxl::VirtualBus* v1 = nullptr;
  dxl::VirtualBusV2* v2 = nullptr;
  sim::SimBusPhysics* sim_physics = nullptr;  ///< with --sim
  dxl::VirtualBusCounters counters() const {
    return v1 != nullptr ? v1->counters() : v2->counters();
  }
};

Status make_bus(const dxl::VirtualBus::Options& options, std::int64_t protocol, bool use_sim,
                const sim::WorldOptions& world_options, Bus& bus) {
  dxl::FirstOrderPhysics::Options physics;
  for (std::size_t i = 0; i < stride::hal::kServoCount; ++i)
    physics.models[i] = options.calibration[i].model;
  std::unique_ptr<dxl::VirtualBusPhysics> motion =
      std::make_unique<dxl::FirstOrderPhysics>(physics);
  if (use_sim) {
    std::unique_ptr<sim::SimWorld> world;
    if (Status s = sim::SimWorld::create(world_options, world); !s) return s;
    auto backed = std::make_unique<sim::SimBusPhysics>(std::move(world));
    bus.sim_physics = backed.get();
    motion = std::move(backed);
  }
  if (protocol == 1) {
    auto v1 = std::make_unique<dxl::VirtualBus>(options, std::move(motion));
    bus.v1 = v1.get();
    bus.responder = std::move(v1);
  } else {
    dxl::VirtualBusV2::Options v2_options;
    v2_options.calibration = options.calibration;
    v2_options.lockstep = options.lockstep;
    v2_options.period_ns = options.period_ns;
    v2_options.faults = options.faults;
    auto v2 = std::make_unique<dxl::VirtualBusV2>(
        v2_options, std::make_unique<dxl::FirstOrderPhysics>(physics));
    bus.v2 = v2.get();
    bus.responder = std::move(v2);
  }
  return {};
}

/// SCHED_FIFO and locked memory, so that replies are not late on a busy machine (a warning
/// each where refused).
void ask_for_realtime() {
  sched_param param{};
  param.sched_priority = 85;
  if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
    errors.warning(std::string("SCHED_FIFO refused (") + std::strerror(errno) + ")");
  }
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    errors.warning(std::string("mlockall refused (") + std::strerror(errno) + ")");
  }
}

/// On exit: the bus counters (and the simulation's state) on stderr, and with --json as one
/// JSON object on stdout.
void report_counters(const Bus& bus, bool json_output) {
  const dxl::VirtualBusCounters c = bus.counters();
  using ull = unsigned long long;
  std::fprintf(
      stderr,
      "stride vbus: %llu instructions, %llu bulk reads, %llu sync reads, %llu sync writes, "
      "%llu replies (%llu with an error); faults: %llu dropped, %llu corrupted, %llu "
      "silenced; %llu bad packets received\n",
      static_cast<ull>(c.instructions), static_cast<ull>(c.bulk_reads),
      static_cast<ull>(c.sync_reads), static_cast<ull>(c.sync_writes), static_cast<ull>(c.replies),
      static_cast<ull>(c.error_replies), static_cast<ull>(c.dropped), static_cast<ull>(c.corrupted),
      static_cast<ull>(c.silenced), static_cast<ull>(c.bad_packets));
  nlohmann::json sim_report;
  if (bus.sim_physics != nullptr) {
    const sim::SimWorld& w = bus.sim_physics->world();
    sim_report = {{"ticks", bus.sim_physics->ticks()},
                  {"sim_time_s", w.time_s()},
                  {"status", sim::to_string(w.status())},
                  {"failure_reason", w.failure_reason()},
                  {"torso_height_m", w.ground_truth().torso.translation().z()},
                  {"state_hash", sim::hash_hex(w.state_hash())}};
    std::fprintf(stderr, "stride vbus: simulation %s after %.2f s, torso height %.3f m\n",
                 sim::to_string(w.status()), w.time_s(),
                 sim_report["torso_height_m"].get<double>());
  }
  if (json_output) {
    nlohmann::json report = {{"instructions", c.instructions}, {"bulk_reads", c.bulk_reads},
                             {"sync_reads", c.sync_reads},     {"sync_writes", c.sync_writes},
                             {"replies", c.replies},           {"error_replies", c.error_replies},
                             {"dropped", c.dropped},           {"corrupted", c.corrupted},
                             {"silenced", c.silenced},         {"bad_packets", c.bad_packets}};
    if (!sim_report.is_null()) report["sim"] = sim_report;
    std::printf("%s\n", report.dump().c_str());
    std::fflush(stdout);
  }
}

int run_vbus(int argc, char** argv) {
  std::vector<std::string> faults;
  std::vector<const char*> rest;
  if (Status s = split_faults(argc, argv, faults, rest); !s) return errors.bad_input(s.message());
  stride::core::CliArgs args;
  declare_options(args);
  if (Status s = args.parse(static_cast<int>(rest.size()), rest.data()); !s)
    return errors.bad_input(s.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  dxl::VirtualBus::Options options;
  std::int64_t protocol = 1;
  bool use_sim = false;
  sim::WorldOptions world;
  if (Status s = read_bus_options(args, faults, options, protocol, use_sim, world); !s)
    return errors.bad_input(s.message());
  Bus bus;
  if (Status s = make_bus(options, protocol, use_sim, world, bus); !s)
    return errors.failure(s.message());

  std::unique_ptr<dxl::PtyBusServer> server;
  if (Status s = dxl::PtyBusServer::create(args.get("link"), server); !s) {
    return errors.failure(s.message());
  }
  if (!args.has("no-rt")) ask_for_realtime();
  struct sigaction action {};
  action.sa_handler = on_vbus_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  std::fprintf(stderr, "stride vbus: serving on %s -> %s (%s%s, %s CM730)\n",
               server->link_path().c_str(), server->slave_path().c_str(),
               options.lockstep ? "lockstep" : "wall clock", use_sim ? ", Simbody simulation" : "",
               dxl::to_string(options.cm730_profile));
  const Status served = server->serve(*bus.responder, g_vbus_stop);
  report_counters(bus, args.has("json"));
  if (!served) {
    return errors.failure(served.message());
  }
  return 0;
}

}  // namespace

STRIDE_COMMAND(vbus, "virtual robot bus (CM730 + 20 MX servos) on a pseudo-terminal", run_vbus);
