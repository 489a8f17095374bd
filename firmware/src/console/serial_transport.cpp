// Console transport on a serial device or pseudo-terminal, opened with libserialport.
//
// Exclusive: TIOCEXCL plus a non-blocking flock, so a second stride-fw (or a picocom, which
// also takes the flock) fails with "in use" instead of stealing bytes. Settings a
// pseudo-terminal rejects are ignored; the link is raw 8N1 without flow control.
// A hang-up (the peer closed a pty, a USB adapter vanished) or a read error reports the link
// as down; the console server then reopens it with back-off.
#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <libserialport.h>

#include "stride/firmware/console/transport.hpp"

namespace stride::fw::console {
namespace {

std::string last_error() {
  char* message = sp_last_error_message();
  std::string text = message != nullptr ? message : "unknown error";
  sp_free_error_message(message);
  return text;
}

class SerialTransport final : public ConsoleTransport {
 public:
  SerialTransport(std::string device, int baud) : device_(std::move(device)), baud_(baud) {}
  ~SerialTransport() override { close(); }

  Status open() override {
    close();
    if (sp_get_port_by_name(device_.c_str(), &port_) != SP_OK) {
      port_ = nullptr;
      return Status::error(device_ + ": " + last_error());
    }
    if (sp_open(port_, SP_MODE_READ_WRITE) != SP_OK) {
      const std::string reason = last_error();
      sp_free_port(port_);
      port_ = nullptr;
      return Status::error(device_ + ": cannot open (" + reason + ")");
    }
    if (sp_get_port_handle(port_, &fd_) != SP_OK || fd_ < 0) {
      close();
      return Status::error(device_ + ": no file descriptor");
    }
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      close();
      return Status::error(device_ + ": in use by another program");
    }
    (void)::ioctl(fd_, TIOCEXCL);
    // A pty refuses some of these; the console works without them.
    (void)sp_set_baudrate(port_, baud_);
    (void)sp_set_bits(port_, 8);
    (void)sp_set_parity(port_, SP_PARITY_NONE);
    (void)sp_set_stopbits(port_, 1);
    (void)sp_set_flowcontrol(port_, SP_FLOWCONTROL_NONE);
    termios raw{};
    if (::tcgetattr(fd_, &raw) == 0) {
      ::cfmakeraw(&raw);
      raw.c_cflag |= CLOCAL | CREAD;
      (void)::tcsetattr(fd_, TCSANOW, &raw);
    }
    return {};
  }

  void close() override {
    if (port_ != nullptr) {
      if (fd_ >= 0) (void)::flock(fd_, LOCK_UN);
      sp_close(port_);
      sp_free_port(port_);
    }
    port_ = nullptr;
    fd_ = -1;
  }

  bool is_open() const override { return port_ != nullptr; }

  long read(char* buffer, std::size_t capacity, int timeout_ms) override {
    if (port_ == nullptr) return -1;
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, timeout_ms);
    if (ready < 0) return errno == EINTR ? 0 : -1;
    if (ready == 0) return 0;
    if ((p.revents & POLLIN) == 0) return -1;  // POLLHUP / POLLERR / POLLNVAL only
    const ssize_t n = ::read(fd_, buffer, capacity);
    if (n > 0) return n;
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) return 0;
    return -1;  // EOF or EIO: the peer hung up or the device vanished
  }

  bool write(std::string_view bytes) override {
    if (port_ == nullptr) return false;
    const sp_return n = sp_blocking_write(port_, bytes.data(), bytes.size(), 1000);
    return n == static_cast<sp_return>(bytes.size());
  }

  bool reopenable() const override { return true; }
  bool wants_echo() const override { return true; }
  std::string name() const override { return device_; }

 private:
  std::string device_;
  int baud_;
  sp_port* port_ = nullptr;
  int fd_ = -1;
};

}  // namespace

std::unique_ptr<ConsoleTransport> make_serial_transport(std::string device, int baud) {
  return std::make_unique<SerialTransport>(std::move(device), baud);
}

}  // namespace stride::fw::console
