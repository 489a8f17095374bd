// The `serial` HAL backend of stride-fw: the Dynamixel bus (CM730 + 20 MX servos, protocol 1.0)
// on a serial port, or on the virtual bus's pseudo-terminal (`stride vbus --link PATH`).
#include <cstdio>

#include <nlohmann/json.hpp>

#include "stride/firmware/dynamixel_config.hpp"
#include "stride/firmware/hal_registry.hpp"
#include "stride/hal/dynamixel/dynamixel_robot.hpp"
#include "stride/hal/dynamixel/serial_port.hpp"

namespace {

using stride::Status;
namespace dxl = stride::hal::dxl;

void declare(stride::core::CliArgs& args) {
  args.option("port", "serial: bus device (e.g. /dev/ttyUSB0, or a stride vbus link)")
      .option("baud", "serial: baud rate", true, "1000000")
      .option("bus-margin-us", "serial: time added to every bus transaction's wire time", true,
              "1500")
      .option("allow-missing", "serial: start even if devices are missing (they are retried)",
              false)
      .option("cm730",
              "serial: the CM730's firmware: stock (ROBOTIS table, 10-bit IMU) or nimbro (NimbRo's "
              "table: 16-bit IMU and a magnetometer, which the walk's heading hold then uses)",
              true, "stock");
}

const char* health_name(stride::hal::DeviceHealth h) {
  switch (h) {
    case stride::hal::DeviceHealth::kOk:
      return "ok";
    case stride::hal::DeviceHealth::kError:
      return "error";
    case stride::hal::DeviceHealth::kTimeout:
      return "timeout";
    case stride::hal::DeviceHealth::kMissing:
      return "missing";
  }
  return "?";
}

/// The bus options' values (no device is opened).
Status check(const stride::core::CliArgs& args, std::int64_t period_ns) {
  if (!args.has("port")) return Status::error("--hal serial needs --port DEV");
  std::int64_t baud = 0;
  if (Status s = args.get_int("baud", baud); !s) return s;
  if (baud <= 0 || !dxl::SerialPort::is_standard_baud(static_cast<std::uint32_t>(baud))) {
    return Status::error("option --baud: unsupported rate " + args.get("baud"));
  }
  std::int64_t margin_us = 0;
  if (Status s = args.get_int("bus-margin-us", margin_us); !s) return s;
  if (margin_us < 0 || margin_us * 1000 > period_ns) {
    return Status::error("option --bus-margin-us: must be between 0 and the loop period");
  }
  dxl::Cm730Profile profile = dxl::Cm730Profile::kStock;
  if (!dxl::parse_cm730_profile(args.get("cm730"), profile)) {
    return Status::error("option --cm730: expected stock or nimbro, got '" + args.get("cm730") +
                         "'");
  }
  return {};
}

Status make(const stride::core::CliArgs& args, std::int64_t period_ns,
            stride::fw::HalInstance& out) {
  if (Status s = check(args, period_ns); !s) return s;
  std::int64_t baud = 0, margin_us = 0;
  (void)args.get_int("baud", baud);  // checked above
  (void)args.get_int("bus-margin-us", margin_us);
  stride::fw::ServoTable table;
  if (Status s = stride::fw::ServoTable::load(args.get("servo-table"), table); !s) return s;
  auto options = stride::fw::dynamixel_options(table, period_ns);
  options.margin_ns = margin_us * 1000;
  options.allow_missing = args.has("allow-missing");
  (void)dxl::parse_cm730_profile(args.get("cm730"), options.cm730_profile);  // checked above
  options.self_paced = false;  // stride-fw's RealtimeRobot paces the loop
  std::unique_ptr<dxl::DynamixelRobot> robot;
  if (Status s = dxl::open_dynamixel_robot(args.get("port"), static_cast<std::uint32_t>(baud),
                                           options, robot);
      !s) {
    return s;
  }
  std::fprintf(stderr, "stride-fw: bus %s at %lld baud: %s\n", args.get("port").c_str(),
               static_cast<long long>(baud), robot->startup_report().c_str());
  const dxl::DynamixelRobot* bus = robot.get();
  out.report = [bus](nlohmann::json& report) {
    const auto& d = bus->diagnostics();
    nlohmann::json devices = nlohmann::json::array();
    std::uint64_t timeouts = 0, corrupt = 0, errors = 0, replies = 0;
    for (std::size_t i = 0; i < d.devices.size(); ++i) {
      const auto& dev = d.devices[i];
      timeouts += dev.timeouts;
      corrupt += dev.corrupt_replies;
      errors += dev.error_replies;
      replies += dev.replies;
      devices.push_back({{"name", bus->device_name(i)},
                         {"replies", dev.replies},
                         {"timeouts", dev.timeouts},
                         {"corrupt", dev.corrupt_replies},
                         {"error_replies", dev.error_replies},
                         {"last_error_flags", dev.last_error_flags},
                         {"health", health_name(dev.health)}});
    }
    report["bus"]["bytes_tx"] = d.bytes_tx;
    report["bus"]["bytes_rx"] = d.bytes_rx;
    report["bus"]["replies"] = replies;
    report["bus"]["timeouts"] = timeouts;
    report["bus"]["corrupt"] = corrupt;
    report["bus"]["error_replies"] = errors;
    report["bus"]["devices"] = devices;
    const std::string health = bus->health_report();
    if (!health.empty()) std::fprintf(stderr, "stride-fw: bus health:\n%s", health.c_str());
  };
  out.robot = std::move(robot);
  out.paced_by_clock = true;
  return {};
}

}  // namespace

STRIDE_HAL_BACKEND(serial, "Dynamixel bus (CM730 + MX servos, protocol 1.0) on a serial port",
                   declare, check, make);
