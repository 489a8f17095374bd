// Console transport on a serial device or pseudo-terminal (tty_port.hpp). A hang-up (the peer
// closed a pty, a USB adapter vanished) or a read error reports the link as down; the console
// server then reopens it with back-off.
#include "stride/firmware/console/transport.hpp"
#include "stride/firmware/console/tty_port.hpp"

namespace stride::fw::console {
namespace {

class SerialTransport final : public ConsoleTransport {
 public:
  SerialTransport(std::string device, int baud) : device_(std::move(device)), baud_(baud) {}

  Status open() override { return port_.open(device_, baud_); }
  void close() override { port_.close(); }
  bool is_open() const override { return port_.is_open(); }
  long read(char* buffer, std::size_t capacity, int timeout_ms) override {
    return port_.read(buffer, capacity, timeout_ms);
  }
  bool write(std::string_view bytes) override { return port_.write(bytes, 1000); }
  bool reopenable() const override { return true; }
  bool wants_echo() const override { return true; }
  std::string name() const override { return device_; }

 private:
  std::string device_;
  int baud_;
  TtyPort port_;
};

}  // namespace

std::unique_ptr<ConsoleTransport> make_serial_transport(std::string device, int baud) {
  return std::make_unique<SerialTransport>(std::move(device), baud);
}

}  // namespace stride::fw::console
