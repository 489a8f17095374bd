// TtyPort implementation: libserialport for real devices, POSIX termios for pseudo-terminals.
#include "stride/firmware/console/tty_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include <libserialport.h>

namespace stride::fw::console {
namespace {

std::string sp_error() {
  char* message = sp_last_error_message();
  std::string text = message != nullptr ? message : "unknown error";
  sp_free_error_message(message);
  return text;
}

long long now_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

Status TtyPort::open(const std::string& path, int baud) {
  close();
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    return Status::error(path + ": " + std::strerror(errno));
  }
  if (!S_ISCHR(st.st_mode)) return Status::error(path + ": not a serial device");
  if (sp_get_port_by_name(path.c_str(), &port_) == SP_OK) {
    if (sp_open(port_, SP_MODE_READ_WRITE) != SP_OK) {
      const std::string reason = sp_error();
      sp_free_port(port_);
      port_ = nullptr;
      return Status::error(path + ": cannot open (" + reason + ")");
    }
    (void)sp_set_baudrate(port_, baud);
    (void)sp_set_bits(port_, 8);
    (void)sp_set_parity(port_, SP_PARITY_NONE);
    (void)sp_set_stopbits(port_, 1);
    (void)sp_set_flowcontrol(port_, SP_FLOWCONTROL_NONE);
    if (sp_get_port_handle(port_, &fd_) != SP_OK || fd_ < 0) {
      fd_ = -1;
      close();
      return Status::error(path + ": no file descriptor");
    }
  } else {
    port_ = nullptr;  // a pseudo-terminal (or a tty libserialport does not describe)
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) return Status::error(path + ": cannot open (" + std::strerror(errno) + ")");
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    close();
    return Status::error(path + ": in use by another program");
  }
  (void)::ioctl(fd_, TIOCEXCL);
  termios raw{};
  if (::tcgetattr(fd_, &raw) == 0) {
    ::cfmakeraw(&raw);
    raw.c_cflag |= CLOCAL | CREAD;
    raw.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS | CSTOPB | PARENB);
    (void)::tcsetattr(fd_, TCSANOW, &raw);
  }
  const int flags = ::fcntl(fd_, F_GETFL);
  if (flags >= 0) (void)::fcntl(fd_, F_SETFL, flags | O_NONBLOCK);
  return {};
}

void TtyPort::close() {
  if (fd_ >= 0) (void)::flock(fd_, LOCK_UN);
  if (port_ != nullptr) {
    sp_close(port_);
    sp_free_port(port_);
  } else if (fd_ >= 0) {
    ::close(fd_);
  }
  port_ = nullptr;
  fd_ = -1;
}

long TtyPort::read(char* buffer, std::size_t capacity, int timeout_ms) {
  if (fd_ < 0) return -1;
  pollfd p{fd_, POLLIN, 0};
  const int ready = ::poll(&p, 1, timeout_ms);
  if (ready < 0) return errno == EINTR ? 0 : -1;
  if (ready == 0) return 0;
  if ((p.revents & POLLIN) == 0) return -1;  // POLLHUP / POLLERR / POLLNVAL without data
  const ssize_t n = ::read(fd_, buffer, capacity);
  if (n > 0) return n;
  if (n < 0 && (errno == EINTR || errno == EAGAIN)) return 0;
  return -1;  // EOF or EIO: the peer hung up or the device vanished
}

bool TtyPort::write(std::string_view bytes, int timeout_ms) {
  if (fd_ < 0) return false;
  const long long deadline = now_ms() + timeout_ms;
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n > 0) {
      bytes.remove_prefix(static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) return false;
    const long long left = deadline - now_ms();
    if (left <= 0) return false;
    pollfd p{fd_, POLLOUT, 0};
    if (::poll(&p, 1, static_cast<int>(left)) < 0 && errno != EINTR) return false;
    if ((p.revents & (POLLERR | POLLHUP | POLLNVAL)) != 0) return false;
  }
  return true;
}

void TtyPort::discard_input() {
  if (fd_ >= 0) (void)::tcflush(fd_, TCIFLUSH);
}

}  // namespace stride::fw::console
