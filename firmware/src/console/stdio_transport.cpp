// Console transport on the process's standard input and output. EOF on stdin ends the
// console (it cannot be reopened); the control loop carries on.
#include <poll.h>
#include <unistd.h>

#include <cerrno>

#include "stride/firmware/console/transport.hpp"

namespace stride::fw::console {
namespace {

class StdioTransport final : public ConsoleTransport {
 public:
  Status open() override {
    if (at_eof_) return Status::error("stdin: end of input");
    open_ = true;
    return {};
  }
  void close() override { open_ = false; }
  bool is_open() const override { return open_; }

  long read(char* buffer, std::size_t capacity, int timeout_ms) override {
    pollfd p{STDIN_FILENO, POLLIN, 0};
    const int ready = ::poll(&p, 1, timeout_ms);
    if (ready < 0) return errno == EINTR ? 0 : -1;
    if (ready == 0) return 0;
    const ssize_t n = ::read(STDIN_FILENO, buffer, capacity);
    if (n > 0) return n;
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) return 0;
    at_eof_ = true;
    return -1;
  }

  bool write(std::string_view bytes) override {
    while (!bytes.empty()) {
      const ssize_t n = ::write(STDOUT_FILENO, bytes.data(), bytes.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      bytes.remove_prefix(static_cast<std::size_t>(n));
    }
    return true;
  }

  bool reopenable() const override { return !at_eof_; }
  bool wants_echo() const override { return false; }
  std::string name() const override { return "stdio"; }

 private:
  bool open_ = false;
  bool at_eof_ = false;
};

}  // namespace

std::unique_ptr<ConsoleTransport> make_stdio_transport() {
  return std::make_unique<StdioTransport>();
}

}  // namespace stride::fw::console
