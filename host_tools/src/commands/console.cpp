// `stride console`: talk to the parameter console of a running stride-fw over a serial device
// or pseudo-terminal. Interactive (line editing and history with libedit) without commands,
// scripted with commands: each positional word is one command line, replies are printed, and
// the exit status is 0 if every reply was ok, 1 if any was err (or the port failed), 2 on bad
// usage. `flash FILE` reads a parameter file on the host and sends it as one line of JSON;
// with --verify every value of the file is read back with `get` and differences are reported.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <editline/readline.h>
#include <nlohmann/json.hpp>

#include "stride/core/cli_args.hpp"
#include "stride/core/json_file.hpp"
#include "stride/firmware/console/line_editor.hpp"
#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/host_tools/console_client.hpp"

namespace stride::tools {
namespace {

const CommandErrors errors("console");

constexpr const char* kUsage =
    "usage: stride console --port DEV [options] [COMMAND...]\n"
    "\n"
    "Talks to the parameter console of stride-fw (stride-fw --console DEV). Without commands\n"
    "it is interactive (line editing, history in ~/.stride_console_history; Ctrl-D quits).\n"
    "Each COMMAND is one console line, e.g. 'get walk.step_time' status 'set stand.gain 40'.\n"
    "'flash FILE' sends the parameter file FILE (read here) as one line of JSON.\n"
    "Exit status: 0 all replies ok, 1 an err reply or a port failure, 2 bad usage.\n\n";

// The console's line limit (stride::fw::console::LineEditor::kDefaultMaxLine).
constexpr std::size_t kMaxConsoleLine = fw::console::LineEditor::kDefaultMaxLine;

// Flattens a parameter file into dotted names (as the firmware does).
void flatten(const nlohmann::json& node, const std::string& prefix,
             std::map<std::string, nlohmann::json>& out) {
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string name = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it.value().is_object()) {
      flatten(it.value(), name, out);
    } else {
      out[name] = it.value();
    }
  }
}

struct FlashFile {
  std::string line;                              ///< "flash {...}"
  std::map<std::string, nlohmann::json> values;  ///< flattened, for --verify
};

Status read_flash_file(const std::string& path, FlashFile& out) {
  nlohmann::json doc;
  if (Status s = stride::core::read_json_file(path, doc); !s) return s;
  if (!doc.is_object()) return Status::error(path + ": expected a JSON object of parameters");
  out.line = "flash " + doc.dump();
  if (out.line.size() > kMaxConsoleLine) {
    return Status::error(path + ": " + std::to_string(out.line.size()) +
                         " bytes as one line; the console accepts lines up to " +
                         std::to_string(kMaxConsoleLine) + " bytes");
  }
  out.values.clear();
  flatten(doc, "", out.values);
  return {};
}

// Reads every value of the file back; returns the difference lines.
Status verify(ConsoleClient& client, const FlashFile& file, int timeout_ms,
              std::vector<std::string>& differences) {
  for (const auto& [name, expected] : file.values) {
    ConsoleReply reply;
    if (Status s = client.command("get " + name, reply, timeout_ms); !s) return s;
    const std::string prefix = "ok " + name + " = ";
    if (!reply.ok() || reply.final_line.rfind(prefix, 0) != 0) {
      differences.push_back(name + ": cannot read back (" + reply.final_line + ")");
      continue;
    }
    const std::string robot = reply.final_line.substr(prefix.size());
    const bool same = value_matches(expected, robot);
    if (!same) differences.push_back(name + ": file " + expected.dump() + ", robot " + robot);
  }
  return {};
}

void print_reply(const ConsoleReply& reply) {
  for (const auto& line : reply.data) std::printf("%s\n", line.c_str());
  std::printf("%s\n", reply.final_line.c_str());
  std::fflush(stdout);
}

int interactive(ConsoleClient& client, int timeout_ms) {
  std::string history;
  if (const char* home = std::getenv("HOME"); home != nullptr) {
    history = std::string(home) + "/.stride_console_history";
  }
  using_history();
  if (!history.empty()) (void)read_history(history.c_str());
  int status = 0;
  for (;;) {
    char* raw = readline("stride> ");
    if (raw == nullptr) break;  // Ctrl-D
    std::string line = raw;
    std::free(raw);
    if (line.find_first_not_of(' ') == std::string::npos) continue;
    add_history(line.c_str());
    if (line == "quit" || line == "exit") break;
    if (line.rfind("flash ", 0) == 0 && line.find('{') == std::string::npos) {
      FlashFile file;
      if (Status s = read_flash_file(line.substr(6), file); !s) {
        std::printf("%s\n", s.message().c_str());
        continue;
      }
      line = file.line;
    }
    ConsoleReply reply;
    if (Status s = client.command(line, reply, timeout_ms); !s) {
      status = errors.failure(s.message());
      break;
    }
    print_reply(reply);
  }
  if (!history.empty()) (void)write_history(history.c_str());
  return status;
}

void declare_options(core::CliArgs& args) {
  args.option("port", "serial device or pseudo-terminal of the console")
      .option("baud", "baud rate", true, "115200")
      .option("timeout", "seconds to wait for each reply", true, "5")
      .option("verify", "after flash FILE, read every value back and report differences", false)
      .option("json", "print one JSON object with every command and reply", false)
      .option("help", "show this help", false);
}

/// The command lines: each positional word is a line; `flash FILE` may also be two words.
std::vector<std::string> command_lines(const std::vector<std::string>& words) {
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (words[i] == "flash" && i + 1 < words.size()) {
      lines.push_back("flash " + words[++i]);
    } else {
      lines.push_back(words[i]);
    }
  }
  return lines;
}

void print_help(const core::CliArgs& args) {
  std::printf("%s%s", kUsage, args.help().c_str());
}

}  // namespace

int run_console(int argc, char** argv) {
  core::CliArgs args;
  declare_options(args);
  if (Status s = args.parse(argc, argv); !s) return errors.bad_input(s.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  if (!args.has("port")) return errors.bad_input("missing --port DEV");
  std::int64_t baud = 0;
  double timeout_s = 0;
  if (Status s = args.get_int("baud", baud); !s) return errors.bad_input(s.message());
  if (Status s = args.get_double("timeout", timeout_s); !s) return errors.bad_input(s.message());
  if (baud <= 0) return errors.bad_input("option --baud: must be positive");
  if (timeout_s <= 0) return errors.bad_input("option --timeout: must be positive");
  const int timeout_ms = static_cast<int>(timeout_s * 1000);

  const std::vector<std::string> lines = command_lines(args.positional());
  // Expand flash FILE into the one-line JSON now, so a bad file is a usage error (exit 2)
  // before anything reaches the robot.
  std::vector<FlashFile> flash_files(lines.size());
  std::vector<bool> is_flash(lines.size(), false);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("flash ", 0) == 0 && lines[i].find('{') == std::string::npos) {
      if (Status s = read_flash_file(lines[i].substr(6), flash_files[i]); !s) {
        return errors.bad_input(s.message());
      }
      is_flash[i] = true;
    }
  }
  if (args.has("verify") && std::find(is_flash.begin(), is_flash.end(), true) == is_flash.end()) {
    return errors.bad_input("--verify needs a 'flash FILE' command");
  }

  ConsoleClient client;
  if (Status s = client.open(args.get("port"), static_cast<int>(baud)); !s) {
    return errors.failure(s.message());
  }
  if (lines.empty()) return interactive(client, timeout_ms);

  const bool json = args.has("json");
  nlohmann::json report = {{"port", args.get("port")}, {"commands", nlohmann::json::array()}};
  bool all_ok = true;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = is_flash[i] ? flash_files[i].line : lines[i];
    ConsoleReply reply;
    if (Status s = client.command(line, reply, timeout_ms); !s) return errors.failure(s.message());
    all_ok = all_ok && reply.ok();
    nlohmann::json entry = {{"command", lines[i]},
                            {"ok", reply.ok()},
                            {"data", reply.data},
                            {"reply", reply.final_line}};
    if (!json) print_reply(reply);
    if (is_flash[i] && args.has("verify") && reply.ok()) {
      std::vector<std::string> differences;
      if (Status s = verify(client, flash_files[i], timeout_ms, differences); !s) {
        return errors.failure(s.message());
      }
      all_ok = all_ok && differences.empty();
      entry["verify"] = {{"checked", flash_files[i].values.size()}, {"differences", differences}};
      if (!json) {
        for (const auto& d : differences) std::printf("differs: %s\n", d.c_str());
        std::printf("verify: %zu of %zu parameters match\n",
                    flash_files[i].values.size() - differences.size(),
                    flash_files[i].values.size());
      }
    }
    report["commands"].push_back(entry);
  }
  report["ok"] = all_ok;
  if (json) std::printf("%s\n", report.dump().c_str());
  return all_ok ? 0 : 1;
}

STRIDE_COMMAND(console, "talk to the parameter console of a running stride-fw", run_console);

}  // namespace stride::tools
