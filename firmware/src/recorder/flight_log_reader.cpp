// Flight log reader: file head, then blocks until the end of the file or the first block that
// is incomplete or fails its CRC.
#include "stride/firmware/recorder/flight_log_reader.hpp"

#include <cstring>
#include <fstream>
#include <iterator>

namespace stride::fw {

namespace fl = flight_log;

std::uint64_t FlightLog::dropped_ticks() const {
  if (has_end && end.contains("ticks_dropped")) return end["ticks_dropped"].get<std::uint64_t>();
  std::uint64_t sum = 0;
  for (const FlightLogTick& t : ticks) sum += t.meta.dropped_before;
  return sum;
}

int FlightLog::parameter_index(const std::string& name) const {
  const auto& list = header["parameters"];
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (list[i]["name"] == name) return static_cast<int>(i);
  }
  return -1;
}

Status read_flight_log(const std::filesystem::path& path, FlightLog& out) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::error(name + ": cannot open for reading");
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  FlightLog log;
  log.file_bytes = bytes.size();
  if (bytes.size() < fl::kFileHeadBytes ||
      std::memcmp(bytes.data(), fl::kMagic.data(), fl::kMagic.size()) != 0) {
    return Status::error(name + ": not a Stride flight log (no STRIDEFL magic)");
  }
  const std::uint32_t version = fl::get_u32(bytes.data() + 8);
  if (version != fl::kFormatVersion) {
    return Status::error(name + ": flight log format version " + std::to_string(version) +
                         " (this build reads " + std::to_string(fl::kFormatVersion) + ")");
  }
  std::size_t at = fl::kFileHeadBytes;
  log.complete_bytes = at;
  bool have_header = false;
  while (at < bytes.size()) {
    const std::string where = " at byte " + std::to_string(at);
    if (bytes.size() - at < fl::kBlockHeadBytes) {
      log.stopped_early = "incomplete block" + where;
      break;
    }
    const std::uint32_t size = fl::get_u32(bytes.data() + at);
    const std::uint32_t type = fl::get_u32(bytes.data() + at + 4);
    if (size > fl::kMaxPayloadBytes) {
      log.stopped_early = "implausible block length" + where;
      break;
    }
    const std::size_t total = fl::kBlockHeadBytes + size + fl::kBlockTailBytes;
    if (bytes.size() - at < total) {
      log.stopped_early = "incomplete block" + where;
      break;
    }
    const std::uint8_t* payload = bytes.data() + at + fl::kBlockHeadBytes;
    const std::uint32_t crc = fl::crc32(payload, size, fl::crc32(bytes.data() + at, 8));
    if (crc != fl::get_u32(payload + size)) {
      log.stopped_early = "CRC mismatch" + where;
      break;
    }
    if (!have_header && type != static_cast<std::uint32_t>(fl::BlockType::kHeader)) {
      return Status::error(name + ": the first block is not the header");
    }
    if (type == static_cast<std::uint32_t>(fl::BlockType::kHeader) ||
        type == static_cast<std::uint32_t>(fl::BlockType::kEnd)) {
      nlohmann::json doc = nlohmann::json::parse(payload, payload + size, nullptr, false);
      if (doc.is_discarded()) {
        log.stopped_early = "unreadable JSON block" + where;
        break;
      }
      if (type == static_cast<std::uint32_t>(fl::BlockType::kHeader)) {
        log.header = std::move(doc);
        have_header = true;
      } else {
        log.end = std::move(doc);
        log.has_end = true;
      }
    } else if (type == static_cast<std::uint32_t>(fl::BlockType::kTick)) {
      FlightLogTick tick;
      std::size_t changes = 0;
      if (!fl::decode_tick(payload, size, tick.meta, tick.sensors, tick.commands, changes)) {
        log.stopped_early = "malformed tick block" + where;
        break;
      }
      for (std::size_t i = 0; i < changes; ++i) {
        tick.param_changes.push_back(fl::decode_param_change(payload, i));
      }
      log.ticks.push_back(std::move(tick));
    }  // unknown block types are skipped (a later format may add some)
    at += total;
    log.complete_bytes = at;
  }
  if (!have_header) return Status::error(name + ": no complete header block (file cut short)");
  out = std::move(log);
  return {};
}

}  // namespace stride::fw
