// The bytes both emulated buses put on the wire, pinned: every host conversation of the bus fuzz
// targets' seed corpora (tests/fuzz/corpus/fuzz_virtual_bus{,_v2}), each under every
// combination of the seeded faults and servo models (lockstep time, so the run is
// deterministic), and a scripted one the corpora lack (read chains over an absent ID and a
// device at status return level 0, a changed ID, registered writes), then all of them in one
// long conversation. The replies, the summed return
// delays, the counters and the registers afterwards go into one FNV-1a hash per protocol.
// A change to the buses that is not meant to change their behaviour must keep both hashes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "stride/hal/dynamixel/codec_v1.hpp"
#include "stride/hal/dynamixel/codec_v2.hpp"
#include "stride/hal/dynamixel/virtual_bus.hpp"
#include "stride/hal/dynamixel/virtual_bus_v2.hpp"

namespace stride::hal::dxl {
namespace {

using Bytes = std::vector<std::uint8_t>;

struct Hash {
  std::uint64_t value = 1469598103934665603ULL;
  void add(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      value ^= (v >> (8 * i)) & 0xFF;
      value *= 1099511628211ULL;
    }
  }
  void add(const Bytes& bytes) {
    add(bytes.size());
    for (const std::uint8_t b : bytes) {
      value ^= b;
      value *= 1099511628211ULL;
    }
  }
};

/// The corpus files of `target`, sorted by name: [flags][silent id][overheat id][chunk][bytes].
std::vector<Bytes> corpus(const std::string& target) {
  std::vector<std::filesystem::path> paths;
  for (const auto& e : std::filesystem::directory_iterator(std::string(STRIDE_SOURCE_DIR) +
                                                           "/tests/fuzz/corpus/" + target)) {
    paths.push_back(e.path());
  }
  std::sort(paths.begin(), paths.end());
  std::vector<Bytes> files;
  for (const auto& p : paths) {
    std::ifstream in(p, std::ios::binary);
    files.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return files;
}

/// Appends one instruction packet (protocol 2.0 if `v2`, else 1.0) to `host`.
void add(Bytes& host, bool v2, std::uint8_t id, std::uint8_t code, const Bytes& params) {
  Bytes b(kMaxPacketBytes);
  b.resize(v2 ? v2::encode_instruction(b, id, code, params)
              : v1::encode_instruction(b, id, code, params));
  host.insert(host.end(), b.begin(), b.end());
}

/// [flags][silent id 3][hot id 5][chunk 0] and the script.
Bytes script(bool v2) {
  Bytes h{0, 3, 5, 0};
  namespace in = instruction;
  const std::uint8_t level = v2 ? 68 : 16;
  const std::uint8_t lo = v2 ? 132 : 36;  // present position
  for (int round = 0; round < 2; ++round) {
    if (v2) {
      add(h, true, kBroadcastId, in::kSyncRead, {lo, 0, 4, 0, 1, 77, 2, 3, 4, 5, 6});
      add(h, true, kBroadcastId, in::kBulkRead, {1, lo, 0, 4, 0, 77, lo, 0, 2, 0, 4, lo, 0, 4, 0});
    } else {
      add(h, false, kBroadcastId, in::kBulkRead, {0, 8, 1, lo, 8, 77, lo, 8, 4, lo, 21, 200, 30});
    }
    add(h, v2, 5, in::kWrite, v2 ? Bytes{level, 0, 0} : Bytes{level, 0});  // level 0
    add(h, v2, kBroadcastId, v2 ? in::kSyncRead : in::kBulkRead,
        v2 ? Bytes{lo, 0, 4, 0, 4, 5, 6} : Bytes{0, 8, 4, lo, 8, 5, lo, 8, 6, lo});
    add(h, v2, 5, in::kWrite, v2 ? Bytes{level, 0, 2} : Bytes{level, 2});
    add(h, v2, 6, in::kWrite, v2 ? Bytes{7, 0, 40} : Bytes{3, 40});  // a new ID
    add(h, v2, 40, in::kPing, {});
    add(h, v2, 6, in::kPing, {});
    add(h, v2, kBroadcastId, v2 ? in::kSyncRead : in::kBulkRead,
        v2 ? Bytes{lo, 0, 4, 0, 40, 7} : Bytes{0, 8, 40, lo, 8, 7, lo});
    add(h, v2, 40, in::kWrite, v2 ? Bytes{7, 0, 6} : Bytes{3, 6});
    add(h, v2, 2, in::kRegWrite, v2 ? Bytes{116, 0, 0, 8, 0, 0} : Bytes{30, 0, 8});
    add(h, v2, 2, in::kAction, {});
    add(h, v2, 2, in::kAction, {});
    add(h, v2, kBroadcastId, in::kRegWrite, v2 ? Bytes{116, 0, 0, 9, 0, 0} : Bytes{30, 0, 9});
    add(h, v2, kBroadcastId, in::kAction, {});
    add(h, v2, kBroadcastId, in::kSyncWrite,
        v2 ? Bytes{116, 0, 4, 0, 1, 0, 7, 0, 0, 2, 0, 9, 0, 0} : Bytes{30, 2, 1, 0, 7, 2, 0, 9});
    add(h, v2, 7, v2 ? in::kReboot : in::kReset, {});
    add(h, v2, 3, in::kRead, v2 ? Bytes{250, 0, 20, 0} : Bytes{70, 20});
    add(h, v2, 3, 0x7F, {});
  }
  return h;
}

template <typename Options>
Options options_for(std::uint8_t flags, std::uint8_t silent_id, std::uint8_t hot_id) {
  Options options;
  options.lockstep = true;
  if ((flags & 0x40) != 0) {
    for (std::size_t i = 1; i < options.calibration.size(); i += 2)
      options.calibration[i].model = ServoModelId::kMx64;
  }
  if ((flags & 0x01) != 0) (void)options.faults.add("drop:0.3");
  if ((flags & 0x02) != 0) (void)options.faults.add("corrupt:0.3");
  if ((flags & 0x04) != 0) (void)options.faults.add("silent:" + std::to_string(silent_id));
  if ((flags & 0x08) != 0) (void)options.faults.add("overheat:" + std::to_string(hot_id));
  if ((flags & 0x10) != 0) (void)options.faults.add("start:1");
  (void)options.faults.add("seed:" + std::to_string(7 + flags));
  return options;
}

template <typename Bus>
std::unique_ptr<Bus> make_bus(const typename Bus::Options& options) {
  FirstOrderPhysics::Options physics;
  for (std::size_t i = 0; i < options.calibration.size(); ++i)
    physics.models[i] = options.calibration[i].model;
  return std::make_unique<Bus>(options, std::make_unique<FirstOrderPhysics>(physics));
}

/// Feeds `host` to `bus` in chunks of `chunk` bytes (0: at once) and hashes what comes back.
template <typename Bus>
void converse(Bus& bus, const Bytes& host, std::size_t chunk, Hash& hash) {
  Bytes out;
  std::int64_t delay = 0;
  if (chunk == 0) chunk = std::max<std::size_t>(host.size(), 1);
  for (std::size_t offset = 0; offset < host.size(); offset += chunk) {
    const std::size_t n = std::min(chunk, host.size() - offset);
    bus.receive({host.data() + offset, n}, out, delay);
  }
  hash.add(out);
  hash.add(static_cast<std::uint64_t>(delay));
  const VirtualBusCounters& c = bus.counters();
  for (const std::uint64_t v :
       {c.instructions, c.bad_packets, c.replies, c.error_replies, c.bulk_reads, c.sync_reads,
        c.sync_writes, c.dropped, c.corrupted, c.silenced})
    hash.add(v);
}

void add_registers(const VirtualBus& bus, Hash& hash) {
  for (int id = 0; id < 254; ++id) {
    for (int a = 0; a < 256; ++a)
      hash.add(bus.peek(static_cast<std::uint8_t>(id), static_cast<std::uint8_t>(a)));
  }
}

void add_registers(const VirtualBusV2& bus, Hash& hash) {
  for (int id = 0; id < 254; ++id) {
    for (int a = 0; a < 256; ++a)
      hash.add(bus.peek(static_cast<std::uint8_t>(id), static_cast<std::uint16_t>(a), 1));
  }
}

template <typename Bus>
std::uint64_t wire_hash(const std::string& target, bool v2) {
  std::vector<Bytes> files = corpus(target);
  EXPECT_GE(files.size(), 9U);
  files.push_back(script(v2));
  Hash hash;
  Bytes all;
  for (const Bytes& file : files) {
    if (file.size() < 4) continue;
    const Bytes host(file.begin() + 4, file.end());
    all.insert(all.end(), host.begin(), host.end());
    for (int flags = 0; flags < 0x80; ++flags) {
      if ((flags & 0x20) != 0) continue;  // wall-clock time is not reproducible
      const auto options =
          options_for<typename Bus::Options>(static_cast<std::uint8_t>(flags), file[1], file[2]);
      auto bus = make_bus<Bus>(options);
      converse(*bus, host, file[3], hash);
      add_registers(*bus, hash);
    }
  }
  // One long conversation in 13-byte reads: servo 3 silent, servo 5 hot, the faults on.
  for (const std::uint8_t flags : {0x00, 0x1F, 0x5B}) {
    auto bus = make_bus<Bus>(options_for<typename Bus::Options>(flags, 3, 5));
    for (int round = 0; round < 4; ++round) converse(*bus, all, 13, hash);
    add_registers(*bus, hash);
  }
  return hash.value;
}

TEST(VirtualBusWire, Protocol1RepliesAreByteForByteThePinnedOnes) {
  const std::uint64_t h = wire_hash<VirtualBus>("fuzz_virtual_bus", false);
  RecordProperty("hash", std::to_string(h));
  EXPECT_EQ(h, 0xbe789e70a842034eULL) << "hash 0x" << std::hex << h;
}

TEST(VirtualBusWire, Protocol2RepliesAreByteForByteThePinnedOnes) {
  const std::uint64_t h = wire_hash<VirtualBusV2>("fuzz_virtual_bus_v2", true);
  RecordProperty("hash", std::to_string(h));
  EXPECT_EQ(h, 0x3c14d8837f9b568cULL) << "hash 0x" << std::hex << h;
}

}  // namespace
}  // namespace stride::hal::dxl
