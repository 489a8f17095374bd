// Fault items and reply faults of the emulated buses (see virtual_bus_faults.hpp).
#include "stride/hal/dynamixel/virtual_bus_faults.hpp"

#include <cstdlib>

namespace stride::hal::dxl {

namespace {

bool parse_probability(const std::string& text, double& out) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !(v >= 0.0 && v <= 1.0)) return false;
  out = v;
  return true;
}

bool parse_uint(const std::string& text, std::uint64_t max, std::uint64_t& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (*end != '\0' || text[0] == '-' || v > max) return false;
  out = v;
  return true;
}

}  // namespace

Status VirtualBusFaults::add(const std::string& spec) {
  const auto colon = spec.find(':');
  if (colon == std::string::npos) {
    return Status::error("fault '" + spec +
                         "': expected KIND:VALUE (drop:P, corrupt:P, silent:ID, "
                         "overheat:ID, start:CYCLES)");
  }
  const std::string kind = spec.substr(0, colon);
  const std::string value = spec.substr(colon + 1);
  std::uint64_t n = 0;
  if (kind == "drop" || kind == "corrupt") {
    double p = 0.0;
    if (!parse_probability(value, p)) {
      return Status::error("fault '" + spec + "': probability must be in [0, 1]");
    }
    (kind == "drop" ? drop_probability : corrupt_probability) = p;
  } else if (kind == "silent" || kind == "overheat") {
    if (!parse_uint(value, 253, n)) return Status::error("fault '" + spec + "': bad device ID");
    (kind == "silent" ? silent : overheat)[n] = true;
  } else if (kind == "start") {
    if (!parse_uint(value, 1'000'000'000ULL, n)) {
      return Status::error("fault '" + spec + "': bad cycle count");
    }
    start_after_cycles = n;
  } else if (kind == "seed") {
    if (!parse_uint(value, ~0ULL, n)) return Status::error("fault '" + spec + "': bad seed");
    seed = n;
  } else {
    return Status::error("fault '" + spec + "': unknown kind '" + kind + "'");
  }
  return {};
}

bool inject_reply_faults(const VirtualBusFaults& faults, std::mt19937_64& rng,
                         std::span<std::uint8_t> packet, VirtualBusCounters& counters) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  if (faults.drop_probability > 0.0 && uniform(rng) < faults.drop_probability) {
    ++counters.dropped;
    return false;
  }
  if (faults.corrupt_probability > 0.0 && uniform(rng) < faults.corrupt_probability &&
      packet.size() > 2) {
    std::uniform_int_distribution<std::size_t> pos(2, packet.size() - 1);
    std::uniform_int_distribution<int> flip(1, 255);
    packet[pos(rng)] ^= static_cast<std::uint8_t>(flip(rng));
    ++counters.corrupted;
  }
  return true;
}

}  // namespace stride::hal::dxl
