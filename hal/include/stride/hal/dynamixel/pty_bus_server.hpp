// PtyBusServer: serves an emulated bus (VirtualBus, VirtualBusV2) on a pseudo-terminal, so that any
// program that opens a serial port (stride-fw --hal serial, stride dxl) can talk to the emulated
// robot.
//
// create() opens a pty master (posix_openpt; where /dev/ptmx belongs to another devpts
// instance than the one mounted on /dev/pts, as in some containers, /dev/pts/ptmx instead),
// puts the line in raw mode, and makes `link_path` a symlink to the slave. serve() answers
// packets until `stop` becomes true, waiting the devices' return delay before each reply batch.
// The link is removed on destruction.
#pragma once

#include <atomic>
#include <memory>
#include <string>

#include "stride/core/status.hpp"
#include "stride/hal/dynamixel/bus_responder.hpp"

namespace stride::hal::dxl {

class PtyBusServer {
 public:
  static Status create(const std::string& link_path, std::unique_ptr<PtyBusServer>& out);
  ~PtyBusServer();
  PtyBusServer(const PtyBusServer&) = delete;
  PtyBusServer& operator=(const PtyBusServer&) = delete;

  /// Serves `bus` until `stop` is set (checked at least every 50 ms). Returns an error only if
  /// the pty itself fails.
  Status serve(BusResponder& bus, const std::atomic<bool>& stop);

  const std::string& slave_path() const { return slave_path_; }
  const std::string& link_path() const { return link_path_; }

 private:
  PtyBusServer() = default;
  int master_fd_ = -1;
  int slave_keepalive_fd_ = -1;  ///< keeps the line up while no client has it open
  std::string slave_path_;
  std::string link_path_;
};

}  // namespace stride::hal::dxl
