// ConsoleClient implementation (see the header).
#include "stride/host_tools/console_client.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>

#include <nlohmann/json.hpp>

namespace stride::tools {
namespace {

long long now_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

bool is_final_line(const std::string& line) {
  return line == "ok" || line.rfind("ok ", 0) == 0 || line.rfind("err ", 0) == 0;
}

bool value_matches(const nlohmann::json& expected, const std::string& robot_text) {
  if (expected.is_boolean()) return robot_text == (expected.get<bool>() ? "true" : "false");
  if (!expected.is_number() || robot_text.empty()) return false;
  char* end = nullptr;
  const double value = std::strtod(robot_text.c_str(), &end);
  const double want = expected.get<double>();
  return *end == '\0' && std::fabs(value - want) <= 1e-9 * std::max(1.0, std::fabs(want));
}

Status ConsoleClient::open(const std::string& port, int baud) {
  if (Status s = port_.open(port, baud); !s) return s;
  // Abandon whatever was typed on the console before us, then forget its output.
  if (!port_.write("\x03", 1000)) return Status::error(port + ": cannot write");
  drain(150);
  return {};
}

void ConsoleClient::drain(int quiet_ms) {
  char buffer[4096];
  const long long give_up = now_ms() + 2000;
  while (now_ms() < give_up && port_.read(buffer, sizeof buffer, quiet_ms) > 0) {
  }
  pending_.clear();
}

Status ConsoleClient::read_line(std::string& line, long long deadline_ms) {
  char buffer[4096];
  for (;;) {
    if (const auto eol = pending_.find('\n'); eol != std::string::npos) {
      line = pending_.substr(0, eol);
      pending_.erase(0, eol + 1);
      while (!line.empty() && line.back() == '\r') line.pop_back();
      while (line.rfind("> ", 0) == 0) line.erase(0, 2);  // prompts before the line
      return {};
    }
    const long long left = deadline_ms - now_ms();
    if (left <= 0) return Status::error("the console did not answer in time");
    const long n = port_.read(buffer, sizeof buffer, static_cast<int>(left < 100 ? left : 100));
    if (n < 0) return Status::error("the port was closed or failed");
    pending_.append(buffer, static_cast<std::size_t>(n));
  }
}

Status ConsoleClient::command(const std::string& line, ConsoleReply& out, int timeout_ms) {
  out = {};
  if (!port_.is_open()) return Status::error("port not open");
  if (!port_.write(line + "\r", timeout_ms)) return Status::error("port write failed");
  const long long deadline = now_ms() + timeout_ms;
  bool seen_echo = false;
  for (;;) {
    std::string received;
    if (Status s = read_line(received, deadline); !s) return s;
    if (!seen_echo && received == line) {
      seen_echo = true;
      out.data.clear();  // whatever came before our echo (a banner) is not part of the reply
      continue;
    }
    if (received.empty()) continue;
    if (is_final_line(received)) {
      out.final_line = received;
      return {};
    }
    out.data.push_back(received);
  }
}

}  // namespace stride::tools
