// FlightRecorder: the control thread's copy into the ring, the writer thread's file output.
#include "stride/firmware/recorder/flight_recorder.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

namespace stride::fw {

namespace fl = flight_log;

namespace {

// Writes all of `data`; returns "" or the reason it could not.
std::string write_all(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return std::strerror(errno);
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return {};
}

}  // namespace

Status FlightRecorder::open(const RecorderOptions& options, const fl::HeaderInputs& header,
                            const Controller& controller, std::unique_ptr<FlightRecorder>& out) {
  const std::string name = options.path.string();
  const int fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    return Status::error("cannot open '" + name + "' for writing: " + std::strerror(errno));
  }
  std::unique_ptr<FlightRecorder> recorder(
      new FlightRecorder(options, header.params->size(), controller, fd));
  std::uint8_t head[fl::kFileHeadBytes] = {};
  std::memcpy(head, fl::kMagic.data(), fl::kMagic.size());
  fl::put_u32(head + 8, fl::kFormatVersion);
  recorder->pending_.assign(head, head + sizeof head);
  const std::string json = fl::make_header(header).dump();
  recorder->append_block(fl::BlockType::kHeader, reinterpret_cast<const std::uint8_t*>(json.data()),
                         json.size());
  recorder->flush_pending();
  if (!recorder->write_error_.empty()) {
    const std::string reason = recorder->write_error_;
    ::close(fd);
    recorder->fd_ = -1;
    recorder->closed_ = true;
    return Status::error("cannot write '" + name + "': " + reason);
  }
  recorder->writer_ = std::thread([r = recorder.get()] { r->writer_main(); });
  out = std::move(recorder);
  return {};
}

FlightRecorder::FlightRecorder(const RecorderOptions& options, std::size_t param_count,
                               const Controller& controller, int fd)
    : options_(options),
      controller_(controller),
      fd_(fd),
      ring_(options.buffer_bytes),
      scratch_(fl::kTickFixedBytes + param_count * fl::kParamChangeBytes),
      changes_(param_count),
      change_slot_(param_count, -1) {
  // The writer thread allocates nothing in steady state either.
  popped_.reserve(scratch_.size());
  pending_.reserve((256U << 10) + scratch_.size() + 64);
}

FlightRecorder::~FlightRecorder() {
  (void)close();
}

void FlightRecorder::on_param_change(ParamHandle handle, double value) noexcept {
  if (handle >= change_slot_.size()) return;
  std::int32_t& slot = change_slot_[handle];
  if (slot < 0) {
    slot = static_cast<std::int32_t>(change_count_);
    changes_[change_count_++] = {handle, value};
  } else {
    changes_[static_cast<std::size_t>(slot)].value = value;  // a dropped tick's change, newer
  }
}

void FlightRecorder::on_tick(hal::Tick tick, const hal::SensorFrame& sensors,
                             const hal::CommandFrame& commands) noexcept {
  fl::TickMeta meta;
  meta.tick = tick;
  meta.dropped_before = pending_dropped_;
  meta.motion = controller_.motion().state();
  meta.fallen = controller_.safety().report().fallen;
  meta.tilt_rad = static_cast<float>(controller_.safety().report().tilt_rad);
  const std::size_t size =
      fl::encode_tick(meta, sensors, commands, changes_.data(), change_count_, scratch_.data());
  if (!ring_.try_push(scratch_.data(), static_cast<std::uint32_t>(size))) {
    ++pending_dropped_;
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return;  // the parameter changes stay pending for the next recorded tick
  }
  pending_dropped_ = 0;
  for (std::size_t i = 0; i < change_count_; ++i) change_slot_[changes_[i].handle] = -1;
  change_count_ = 0;
  recorded_.fetch_add(1, std::memory_order_relaxed);
}

void FlightRecorder::append_block(fl::BlockType type, const std::uint8_t* payload,
                                  std::size_t size) {
  std::uint8_t head[fl::kBlockHeadBytes];
  fl::put_u32(head, static_cast<std::uint32_t>(size));
  fl::put_u32(head + 4, static_cast<std::uint32_t>(type));
  std::uint8_t tail[fl::kBlockTailBytes];
  fl::put_u32(tail, fl::crc32(payload, size, fl::crc32(head, sizeof head)));
  pending_.insert(pending_.end(), head, head + sizeof head);
  pending_.insert(pending_.end(), payload, payload + size);
  pending_.insert(pending_.end(), tail, tail + sizeof tail);
}

void FlightRecorder::flush_pending() {
  if (pending_.empty()) return;
  if (write_error_.empty()) {
    write_error_ = write_all(fd_, pending_.data(), pending_.size());
    if (write_error_.empty()) bytes_written_ += pending_.size();
  }
  pending_.clear();  // after a write error the rest is lost; the loop keeps running
}

bool FlightRecorder::drain() {
  bool any = false;
  while (ring_.try_pop(popped_)) {
    any = true;
    append_block(fl::BlockType::kTick, popped_.data(), popped_.size());
    if (pending_.size() >= (256U << 10)) flush_pending();
  }
  flush_pending();  // whole blocks only: a kill leaves the file at a block boundary or mid-write
  return any;
}

void FlightRecorder::writer_main() {
  using clock = std::chrono::steady_clock;
  auto last_sync = clock::now();
  for (;;) {
    const bool stopping = stop_.load(std::memory_order_acquire);
    const bool any = drain();
    if (clock::now() - last_sync >= std::chrono::milliseconds(options_.sync_every_ms)) {
      if (write_error_.empty()) (void)::fdatasync(fd_);
      last_sync = clock::now();
    }
    if (stopping && !any) return;
    if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(options_.writer_poll_ms));
  }
}

RecorderTotals FlightRecorder::close() {
  if (closed_) return totals_;
  closed_ = true;
  stop_.store(true, std::memory_order_release);
  if (writer_.joinable()) writer_.join();
  totals_.ticks_recorded = recorded_.load();
  totals_.ticks_dropped = dropped_.load();
  const nlohmann::json end = {{"ticks_recorded", totals_.ticks_recorded},
                              {"ticks_dropped", totals_.ticks_dropped},
                              {"buffer_bytes", ring_.capacity()}};
  const std::string json = end.dump();
  append_block(fl::BlockType::kEnd, reinterpret_cast<const std::uint8_t*>(json.data()),
               json.size());
  flush_pending();
  if (write_error_.empty()) (void)::fdatasync(fd_);
  ::close(fd_);
  fd_ = -1;
  totals_.bytes_written = bytes_written_;
  totals_.write_error = write_error_;
  return totals_;
}

}  // namespace stride::fw
