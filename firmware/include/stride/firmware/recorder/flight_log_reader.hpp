// Reads a flight log (FLIGHT_LOG.md) back into memory: the header, every complete tick and the
// end block. A log cut short (stride-fw killed, power lost) reads up to its last complete
// block; the reader says where and why it stopped.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/core/status.hpp"
#include "stride/firmware/recorder/flight_log_format.hpp"

namespace stride::fw {

/// One recorded control cycle. Values are the float32 the log holds, widened to double.
struct FlightLogTick {
  flight_log::TickMeta meta;
  hal::SensorFrame sensors{};
  hal::CommandFrame commands{};
  std::vector<flight_log::ParamChange> param_changes;  ///< applied at the start of this tick
};

struct FlightLog {
  nlohmann::json header;  ///< the header block (FLIGHT_LOG.md, "Header")
  std::vector<FlightLogTick> ticks;
  bool has_end = false;  ///< the end block was found (stride-fw stopped cleanly)
  nlohmann::json end;    ///< the end block, if any
  std::uint64_t file_bytes = 0;
  std::uint64_t complete_bytes = 0;  ///< bytes up to the end of the last complete block
  std::string stopped_early;         ///< why reading stopped before the file's end ("" if not)

  /// Ticks the recorder dropped (the sum of every tick's dropped_before, or the end block's
  /// total when present).
  std::uint64_t dropped_ticks() const;
  /// Index of a parameter in the header's list (the handle of param_changes), or -1.
  int parameter_index(const std::string& name) const;
};

/// Reads `path`. Fails (with the file named) only if it cannot be read, is not a flight log,
/// has an unknown format version, or has no complete header block; a damaged or cut tail is
/// reported in `stopped_early`.
Status read_flight_log(const std::filesystem::path& path, FlightLog& out);

}  // namespace stride::fw
