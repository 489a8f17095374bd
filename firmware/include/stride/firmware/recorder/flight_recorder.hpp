// FlightRecorder: stride-fw --record FILE. Writes the header block when it opens, then hears
// every loop cycle on the control thread (LoopRecorder) and copies it into a preallocated
// RecordRing; a writer thread drains the ring into the file. The control thread never waits
// and never does I/O: when the ring is full the tick is dropped whole and counted (its
// parameter changes are carried into the next recorded tick). Format: FLIGHT_LOG.md.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "stride/core/status.hpp"
#include "stride/firmware/control_loop.hpp"
#include "stride/firmware/controller.hpp"
#include "stride/firmware/recorder/flight_log_format.hpp"
#include "stride/firmware/recorder/flight_log_header.hpp"
#include "stride/firmware/recorder/record_ring.hpp"

namespace stride::fw {

struct RecorderOptions {
  std::filesystem::path path;
  std::size_t buffer_bytes = 4U << 20;  ///< ring capacity (about 2,900 ticks)
  int writer_poll_ms = 2;               ///< how often the writer looks at an empty ring
  int sync_every_ms = 1000;             ///< fdatasync period (a dead battery loses at most this)
};

/// Totals of a recording, final after close().
struct RecorderTotals {
  std::uint64_t ticks_recorded = 0;  ///< ticks put into the ring
  std::uint64_t ticks_dropped = 0;   ///< ticks refused because the ring was full
  std::uint64_t bytes_written = 0;   ///< bytes in the file
  std::string write_error;           ///< the first write error ("" none); later blocks lost
};

class FlightRecorder final : public LoopRecorder {
 public:
  /// Creates (truncates) the file, writes the header block and starts the writer thread.
  /// `controller` gives the motion state of each tick and must outlive the recorder. An error
  /// names the file and the reason.
  static Status open(const RecorderOptions& options, const flight_log::HeaderInputs& header,
                     const Controller& controller, std::unique_ptr<FlightRecorder>& out);
  ~FlightRecorder() override;

  void on_param_change(ParamHandle handle, double value) noexcept override;
  void on_tick(hal::Tick tick, const hal::SensorFrame& sensors,
               const hal::CommandFrame& commands) noexcept override;

  /// Stops the writer after it has written everything in the ring, then writes the end block
  /// and closes the file. Call after the loop has stopped. Idempotent.
  RecorderTotals close();

  std::uint64_t dropped_ticks() const noexcept { return dropped_.load(std::memory_order_relaxed); }

 private:
  FlightRecorder(const RecorderOptions& options, std::size_t param_count,
                 const Controller& controller, int fd);
  void writer_main();
  bool drain();  // writer thread: moves the ring's records into the file; false if none
  void append_block(flight_log::BlockType type, const std::uint8_t* payload, std::size_t size);
  void flush_pending();

  RecorderOptions options_;
  const Controller& controller_;
  int fd_ = -1;
  flight_log::RecordRing ring_;

  // Control thread only (preallocated at open).
  std::vector<std::uint8_t> scratch_;
  std::vector<flight_log::ParamChange> changes_;
  std::vector<std::int32_t> change_slot_;  ///< per parameter: index in changes_, or -1
  std::size_t change_count_ = 0;
  std::uint32_t pending_dropped_ = 0;

  std::atomic<std::uint64_t> recorded_{0};
  std::atomic<std::uint64_t> dropped_{0};

  // Writer thread only (until joined).
  std::vector<std::uint8_t> popped_;
  std::vector<std::uint8_t> pending_;
  std::uint64_t bytes_written_ = 0;
  std::string write_error_;

  std::atomic<bool> stop_{false};
  std::thread writer_;
  bool closed_ = false;
  RecorderTotals totals_;
};

}  // namespace stride::fw
