// `stride dxl --port DEV scan|ping|read|write|monitor`: bench work on a Dynamixel bus (real
// servos through a USB adapter or the CM730, or the virtual bus of `stride vbus`).
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/cli_args.hpp"
#include "stride/hal/dynamixel/codec_v1.hpp"
#include "stride/hal/dynamixel/codec_v2.hpp"
#include "stride/hal/dynamixel/control_table.hpp"
#include "stride/hal/dynamixel/packet_parser.hpp"
#include "stride/hal/dynamixel/serial_port.hpp"
#include "stride/hal/dynamixel/units.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"

namespace {

namespace dxl = stride::hal::dxl;
using stride::Status;

std::atomic<bool> g_dxl_stop{false};
void on_dxl_signal(int) {
  g_dxl_stop.store(true);
}

const stride::tools::CommandErrors errors("dxl");

bool parse_number(const std::string& text, long max, long& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 0);
  if (*end != '\0' || errno != 0 || v < 0 || v > max) return false;
  out = v;
  return true;
}

// One request/response exchange on the bus, for either protocol.
class Client {
 public:
  Client(std::unique_ptr<dxl::SerialPort> port, dxl::Protocol protocol, std::int64_t timeout_ns)
      : port_(std::move(port)),
        parser_(protocol, dxl::PacketParser::Role::kHost),
        protocol_(protocol),
        timeout_ns_(timeout_ns) {}
  dxl::Protocol protocol() const { return protocol_; }

  bool transact(std::span<const std::uint8_t> packet, std::uint8_t id, dxl::Packet* reply) {
    port_->discard_input();
    parser_.reset();
    const std::int64_t t0 = dxl::monotonic_ns();
    if (!port_->write(packet, t0 + timeout_ns_)) return false;
    if (id == dxl::kBroadcastId) return true;
    const std::int64_t deadline =
        dxl::monotonic_ns() + timeout_ns_ + dxl::wire_time_ns(packet.size() + 300, port_->baud());
    std::array<std::uint8_t, 512> rx{};
    dxl::Packet p;
    for (;;) {
      while (parser_.next(p)) {
        if (p.id == id && p.is_status) {
          if (reply != nullptr) *reply = p;
          return true;
        }
      }
      const auto n = port_->read_some(rx, deadline);
      if (n <= 0) return false;
      (void)parser_.feed(std::span<const std::uint8_t>(rx.data(), static_cast<std::size_t>(n)));
    }
  }
  bool ping(std::uint8_t id) {
    std::array<std::uint8_t, 16> tx{};
    const std::size_t n = protocol_ == dxl::Protocol::kV1 ? dxl::v1::encode_ping(tx, id)
                                                          : dxl::v2::encode_ping(tx, id);
    return transact(std::span(tx.data(), n), id, nullptr);
  }
  bool read(std::uint8_t id, std::uint16_t address, std::uint16_t length, dxl::Packet& reply) {
    std::array<std::uint8_t, 32> tx{};
    const std::size_t n = protocol_ == dxl::Protocol::kV1
                              ? dxl::v1::encode_read(tx, id, static_cast<std::uint8_t>(address),
                                                     static_cast<std::uint8_t>(length))
                              : dxl::v2::encode_read(tx, id, address, length);
    return transact(std::span(tx.data(), n), id, &reply) && reply.param_count == length;
  }
  bool write(std::uint8_t id, std::uint16_t address, std::span<const std::uint8_t> data,
             dxl::Packet* reply) {
    std::array<std::uint8_t, 64> tx{};
    const std::size_t n =
        protocol_ == dxl::Protocol::kV1
            ? dxl::v1::encode_write(tx, id, static_cast<std::uint8_t>(address), data)
            : dxl::v2::encode_write(tx, id, address, data);
    return transact(std::span(tx.data(), n), id, reply);
  }
  std::optional<std::uint16_t> model(std::uint8_t id) {
    dxl::Packet reply;
    if (!read(id, 0, 2, reply)) return std::nullopt;
    return dxl::read_u16(reply.params.data());
  }

 private:
  std::unique_ptr<dxl::SerialPort> port_;
  dxl::PacketParser parser_;
  dxl::Protocol protocol_;
  std::int64_t timeout_ns_;
};

std::string model_label(std::uint16_t model, dxl::Protocol protocol) {
  const auto* t = dxl::table_for_model(model, protocol);
  return t != nullptr ? std::string(t->model_name) : "model " + std::to_string(model);
}

// Resolves "goal_position" or "30" on device `id` to (address, size).
Status resolve_register(Client& client, std::uint8_t id, const std::string& text,
                        std::uint16_t& address, std::uint8_t& size) {
  long number = 0;
  const auto model = client.model(id);
  const dxl::ControlTable* table =
      model ? dxl::table_for_model(*model, client.protocol()) : nullptr;
  if (parse_number(text, 65535, number)) {
    address = static_cast<std::uint16_t>(number);
    const dxl::Register* r = table != nullptr ? table->at(address) : nullptr;
    size = r != nullptr ? r->size : 1;
    return {};
  }
  if (table == nullptr) {
    return Status::error("register '" + text + "': device " + std::to_string(id) +
                         " did not report a known model; give the address as a number");
  }
  const dxl::Register* r = table->find(text);
  if (r == nullptr) {
    return Status::error("register '" + text + "' is not in the " + std::string(table->model_name) +
                         " control table");
  }
  address = r->address;
  size = r->size;
  return {};
}

void declare_options(stride::core::CliArgs& args) {
  args.option("port", "bus device (e.g. /dev/ttyUSB0 or a stride vbus link)")
      .option("baud", "baud rate", true, "1000000")
      .option("protocol", "Dynamixel protocol 1 or 2", true, "1")
      .option("timeout-ms", "reply timeout per request [ms]", true, "20")
      .option("size", "write: bytes to write (default: the register's size)")
      .option("count", "monitor: number of readings (default: until Ctrl-C)")
      .option("interval-ms", "monitor: time between readings [ms]", true, "100")
      .option("max-id", "scan: highest ID to try", true, "253")
      .option("json", "print results as one JSON object", false)
      .option("help", "show this help", false);
}

void print_help(const stride::core::CliArgs& args) {
  std::printf(
      "usage: stride dxl --port DEV [options] COMMAND\n\n"
      "commands:\n"
      "  scan                      ping IDs 0..max-id, list devices and models\n"
      "  ping ID                   ping one device, print its model\n"
      "  read ID REGISTER [LEN]    read a register (name, e.g. present_position, or address)\n"
      "  write ID REGISTER VALUE   write a register (ID 254 = broadcast)\n"
      "  monitor [ID...]           print position, speed, load, voltage, temperature of\n"
      "                            servos (protocol 1.0, default IDs 1-20)\n\n%s",
      args.help().c_str());
}

/// The numeric options, checked.
struct BusOptions {
  std::int64_t baud = 0, protocol_number = 0, timeout_ms = 0, max_id = 0, interval_ms = 0,
               count = -1;
};

Status read_bus_options(const stride::core::CliArgs& args, BusOptions& o) {
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, std::int64_t*>>{{"baud", &o.baud},
                                                          {"protocol", &o.protocol_number},
                                                          {"timeout-ms", &o.timeout_ms},
                                                          {"max-id", &o.max_id},
                                                          {"interval-ms", &o.interval_ms},
                                                          {"count", &o.count}}) {
    if (Status s = args.get_int(name, *value); !s) return s;
  }
  if (o.baud <= 0 || !dxl::SerialPort::is_standard_baud(static_cast<std::uint32_t>(o.baud)))
    return Status::error("option --baud: unsupported rate " + args.get("baud"));
  if (o.protocol_number != 1 && o.protocol_number != 2)
    return Status::error("option --protocol: must be 1 or 2");
  if (o.timeout_ms <= 0 || o.timeout_ms > 10000)
    return Status::error("option --timeout-ms: must be 1..10000");
  if (o.max_id < 0 || o.max_id > 253) return Status::error("option --max-id: must be 0..253");
  if (o.interval_ms < 0) return Status::error("option --interval-ms: must be >= 0");
  return {};
}

/// The command word and its ID and argument count; errors are bad input.
Status check_command(const std::vector<std::string>& words, long& id) {
  const std::string& command = words[0];
  if (command != "scan" && command != "ping" && command != "read" && command != "write" &&
      command != "monitor")
    return Status::error("unknown command '" + command + "' (scan, ping, read, write, monitor)");
  if ((command == "ping" || command == "read" || command == "write") &&
      !(words.size() > 1 && parse_number(words[1], 254, id)))
    return Status::error(command + ": missing or bad ID '" + (words.size() > 1 ? words[1] : "") +
                         "'");
  if ((command == "read" && words.size() < 3) || (command == "write" && words.size() < 4))
    return Status::error(command + ": missing arguments (see --help)");
  return {};
}

/// scan: ping IDs 0..max_id and list the devices that answer.
int scan(Client& client, dxl::Protocol protocol, std::int64_t max_id, bool json) {
  nlohmann::json found = nlohmann::json::array();
  for (int scan_id = 0; scan_id <= max_id && !g_dxl_stop.load(); ++scan_id) {
    if (!client.ping(static_cast<std::uint8_t>(scan_id))) continue;
    const auto model = client.model(static_cast<std::uint8_t>(scan_id));
    const std::string label = model ? model_label(*model, protocol) : "model unknown";
    found.push_back({{"id", scan_id}, {"model", model ? *model : 0}, {"name", label}});
    if (!json) std::printf("%3d  %s\n", scan_id, label.c_str());
  }
  if (json) {
    std::printf("%s\n", nlohmann::json{{"devices", found}}.dump().c_str());
  } else {
    std::printf("%zu device(s) found\n", found.size());
  }
  return 0;
}

/// ping ID: one device and its model.
int ping(Client& client, dxl::Protocol protocol, long id, bool json) {
  const auto dev = static_cast<std::uint8_t>(id);
  if (!client.ping(dev)) return errors.failure("no reply from ID " + std::to_string(id));
  const auto model = client.model(dev);
  const std::string label = model ? model_label(*model, protocol) : "model unknown";
  if (json) {
    std::printf(
        "%s\n",
        nlohmann::json{{"id", id}, {"model", model ? *model : 0}, {"name", label}}.dump().c_str());
  } else {
    std::printf("%ld  %s\n", id, label.c_str());
  }
  return 0;
}

/// read ID REGISTER [LEN]
int read_register(Client& client, const std::vector<std::string>& words, long id,
                  std::uint16_t address, std::uint8_t size, bool json) {
  const auto dev = static_cast<std::uint8_t>(id);
  long length = size;
  if (words.size() > 3 && !parse_number(words[3], 255, length)) {
    return errors.bad_input("read: bad length '" + words[3] + "'");
  }
  dxl::Packet reply;
  if (!client.read(dev, address, static_cast<std::uint16_t>(length), reply)) {
    return errors.failure("no valid reply from ID " + std::to_string(id));
  }
  std::uint32_t value = 0;
  for (std::size_t k = 0; k < reply.param_count && k < 4; ++k) value |= reply.params[k] << (8 * k);
  if (json) {
    std::printf("%s\n", nlohmann::json{{"id", id},
                                       {"address", address},
                                       {"bytes",
                                        std::vector<int>(reply.params.begin(),
                                                         reply.params.begin() + reply.param_count)},
                                       {"value", value},
                                       {"error", reply.error}}
                            .dump()
                            .c_str());
  } else {
    std::printf("ID %ld address %u: %u", id, address, value);
    if (reply.error != 0) std::printf("  (error 0x%02x)", reply.error);
    std::printf("\n");
  }
  return 0;
}

/// write ID REGISTER VALUE (--size bytes, or the register's size).
int write_register(Client& client, const stride::core::CliArgs& args,
                   const std::vector<std::string>& words, long id, std::uint16_t address,
                   std::uint8_t size, bool json) {
  const auto dev = static_cast<std::uint8_t>(id);
  long value = 0;
  if (!parse_number(words[3], 0xFFFFFFFL, value))
    return errors.bad_input("write: bad value '" + words[3] + "'");
  std::int64_t forced = 0;
  if (args.has("size")) {
    if (Status s = args.get_int("size", forced); !s || forced < 1 || forced > 4) {
      return errors.bad_input("option --size: must be 1..4");
    }
    size = static_cast<std::uint8_t>(forced);
  }
  if (size < 4 && static_cast<unsigned long>(value) >= (1UL << (8 * size))) {
    return errors.bad_input("write: value " + words[3] + " does not fit in " +
                            std::to_string(size) + " byte(s)");
  }
  std::array<std::uint8_t, 4> data{};
  for (std::uint8_t k = 0; k < size; ++k) data[k] = static_cast<std::uint8_t>(value >> (8 * k));
  dxl::Packet reply;
  const bool answered = client.write(dev, address, std::span(data.data(), size), &reply);
  if (dev != dxl::kBroadcastId && answered && reply.error != 0) {
    return errors.failure("ID " + std::to_string(id) + " refused the write (error 0x" + [&] {
      char b[8];
      std::snprintf(b, sizeof b, "%02x", reply.error);
      return std::string(b);
    }() + ")");
  }
  if (json) {
    std::printf("%s\n", nlohmann::json{{"id", id},
                                       {"address", address},
                                       {"value", value},
                                       {"acknowledged", answered && dev != dxl::kBroadcastId}}
                            .dump()
                            .c_str());
  } else {
    std::printf("ID %ld address %u <- %ld%s\n", id, address, value,
                answered && dev != dxl::kBroadcastId ? "" : " (no status reply)");
  }
  return 0;
}

/// monitor [ID...]: position, speed, load, voltage and temperature of servos, --count times
/// (or until Ctrl-C) every --interval-ms.
int monitor(Client& client, dxl::Protocol protocol, const std::vector<std::string>& words,
            std::int64_t count, std::int64_t interval_ms, bool json) {
  if (protocol != dxl::Protocol::kV1) return errors.bad_input("monitor: protocol 1.0 only");
  std::vector<std::uint8_t> ids;
  for (std::size_t k = 1; k < words.size(); ++k) {
    long v = 0;
    if (!parse_number(words[k], 253, v))
      return errors.bad_input("monitor: bad ID '" + words[k] + "'");
    ids.push_back(static_cast<std::uint8_t>(v));
  }
  if (ids.empty()) {
    for (std::uint8_t k = 1; k <= 20; ++k) ids.push_back(k);
  }
  std::signal(SIGINT, on_dxl_signal);
  std::signal(SIGTERM, on_dxl_signal);
  nlohmann::json readings = nlohmann::json::array();
  for (std::int64_t n = 0; (count < 0 || n < count) && !g_dxl_stop.load(); ++n) {
    nlohmann::json row = nlohmann::json::array();
    for (const std::uint8_t sid : ids) {
      dxl::Packet reply;
      if (!client.read(sid, dxl::mx1::kPresentPosition, 8, reply)) {
        if (!json) std::printf("%3u  no reply\n", sid);
        row.push_back({{"id", sid}, {"reply", false}});
        continue;
      }
      const auto* p = reply.params.data();
      const int position = dxl::read_u16(p);
      const int speed = dxl::units::signed_from_bit10(dxl::read_u16(p + 2));
      const int load = dxl::units::signed_from_bit10(dxl::read_u16(p + 4));
      if (!json) {
        std::printf("%3u  pos %4d  speed %5d  load %5d  %4.1f V  %3d C  err 0x%02x\n", sid,
                    position, speed, load, p[6] * 0.1, p[7], reply.error);
      }
      row.push_back({{"id", sid},
                     {"reply", true},
                     {"position", position},
                     {"speed", speed},
                     {"load", load},
                     {"voltage_v", p[6] * 0.1},
                     {"temperature_c", p[7]},
                     {"error", reply.error}});
    }
    if (json) readings.push_back(row);
    if (!json) std::printf("\n");
    std::fflush(stdout);
    if (interval_ms > 0 && (count < 0 || n + 1 < count)) {
      timespec ts{static_cast<time_t>(interval_ms / 1000),
                  static_cast<long>(interval_ms % 1000) * 1'000'000};
      nanosleep(&ts, nullptr);
    }
  }
  if (json) std::printf("%s\n", nlohmann::json{{"readings", readings}}.dump().c_str());
  return 0;
}

int run_dxl(int argc, char** argv) {
  stride::core::CliArgs args;
  declare_options(args);
  if (Status s = args.parse(argc, argv); !s) return errors.bad_input(s.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  const auto& words = args.positional();
  if (words.empty()) return errors.bad_input("missing command (scan, ping, read, write, monitor)");
  if (!args.has("port")) return errors.bad_input("missing --port DEV");
  BusOptions o;
  if (Status s = read_bus_options(args, o); !s) return errors.bad_input(s.message());
  const std::string command = words[0];
  const bool json = args.has("json");
  long id = 0;
  if (Status s = check_command(words, id); !s) return errors.bad_input(s.message());

  std::unique_ptr<dxl::SerialPort> port;
  if (Status s = dxl::SerialPort::open(args.get("port"), static_cast<std::uint32_t>(o.baud), port);
      !s) {
    return errors.failure(s.message());
  }
  const auto protocol = o.protocol_number == 1 ? dxl::Protocol::kV1 : dxl::Protocol::kV2;
  Client client(std::move(port), protocol, o.timeout_ms * 1'000'000);

  if (command == "scan") return scan(client, protocol, o.max_id, json);
  if (command == "ping") return ping(client, protocol, id, json);
  if (command == "read" || command == "write") {
    std::uint16_t address = 0;
    std::uint8_t size = 1;
    if (Status s = resolve_register(client, static_cast<std::uint8_t>(id), words[2], address, size);
        !s)
      return errors.bad_input(s.message());
    if (command == "read") return read_register(client, words, id, address, size, json);
    return write_register(client, args, words, id, address, size, json);
  }
  return monitor(client, protocol, words, o.count, o.interval_ms, json);
}

}  // namespace

STRIDE_COMMAND(dxl, "Dynamixel bench tool: scan, ping, read, write, monitor", run_dxl);
