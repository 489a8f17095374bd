// SerialPort implementation (see serial_port.hpp).
#include "stride/hal/dynamixel/serial_port.hpp"

#include <fcntl.h>
#include <libserialport.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>

namespace stride::hal::dxl {

std::int64_t monotonic_ns() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000LL + ts.tv_nsec;
}

namespace {

constexpr std::array<std::uint32_t, 17> kStandardBauds = {
    9600,   19200,  38400,   57600,   115200,  200000,  230400,  250000, 400000,
    460800, 500000, 1000000, 2000000, 2250000, 2500000, 3000000, 4000000};

speed_t termios_speed(std::uint32_t baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 500000:
      return B500000;
    case 1000000:
      return B1000000;
    case 2000000:
      return B2000000;
    case 2500000:
      return B2500000;
    case 3000000:
      return B3000000;
    case 4000000:
      return B4000000;
    default:
      return B0;
  }
}

bool is_pty_slave(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISCHR(st.st_mode)) return false;
  const unsigned maj = major(st.st_rdev);
  return maj >= 136 && maj <= 143;  // UNIX98 pty slaves
}

// Sets the USB-serial latency timer to 1 ms where the device has one. Quiet otherwise.
bool set_latency_timer(const std::string& path) {
  std::error_code ec;
  const auto real = std::filesystem::canonical(path, ec);
  if (ec) return false;
  const auto sysfs =
      std::filesystem::path("/sys/bus/usb-serial/devices") / real.filename() / "latency_timer";
  if (!std::filesystem::exists(sysfs, ec)) return false;
  std::ofstream out(sysfs);
  if (!out) return false;
  out << "1\n";
  out.flush();
  return static_cast<bool>(out);
}

std::string sp_error(const char* what) {
  char* message = sp_last_error_message();
  std::string text = std::string(what) + ": " + (message != nullptr ? message : "unknown error");
  if (message != nullptr) sp_free_error_message(message);
  return text;
}

}  // namespace

bool SerialPort::is_standard_baud(std::uint32_t baud) {
  for (const std::uint32_t b : kStandardBauds) {
    if (b == baud) return true;
  }
  return false;
}

Status SerialPort::open(const std::string& path, std::uint32_t baud,
                        std::unique_ptr<SerialPort>& out) {
  if (!is_standard_baud(baud)) {
    return Status::error("serial port " + path + ": unsupported baud rate " + std::to_string(baud));
  }
  std::unique_ptr<SerialPort> port(new SerialPort());
  port->path_ = path;
  port->baud_ = baud;
  port->pty_ = is_pty_slave(path);
  if (port->pty_) {
    port->fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (port->fd_ < 0) {
      return Status::error("serial port " + path + ": " + std::strerror(errno));
    }
    termios tio{};
    if (tcgetattr(port->fd_, &tio) == 0) {
      cfmakeraw(&tio);
      tio.c_cflag |= CLOCAL | CREAD;
      tio.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS | CSTOPB | PARENB);
      const speed_t speed = termios_speed(baud);
      if (speed != B0) (void)cfsetspeed(&tio, speed);  // a pty ignores the rate: harmless
      (void)tcsetattr(port->fd_, TCSANOW, &tio);
    }
  } else {
    if (sp_get_port_by_name(path.c_str(), &port->port_) != SP_OK) {
      port->port_ = nullptr;
      return Status::error("serial port " + path + ": " + sp_error("not found"));
    }
    if (sp_open(port->port_, SP_MODE_READ_WRITE) != SP_OK) {
      const std::string message = sp_error("cannot open");
      sp_free_port(port->port_);
      port->port_ = nullptr;
      return Status::error("serial port " + path + ": " + message);
    }
    if (sp_set_baudrate(port->port_, static_cast<int>(baud)) != SP_OK) {
      return Status::error("serial port " + path + ": " + sp_error("cannot set baud rate"));
    }
    // 8N1, no flow control. Some adapters refuse individual settings they already have;
    // only the baud rate is essential, so the rest is best effort.
    (void)sp_set_bits(port->port_, 8);
    (void)sp_set_parity(port->port_, SP_PARITY_NONE);
    (void)sp_set_stopbits(port->port_, 1);
    (void)sp_set_flowcontrol(port->port_, SP_FLOWCONTROL_NONE);
    if (sp_get_port_handle(port->port_, &port->fd_) != SP_OK || port->fd_ < 0) {
      return Status::error("serial port " + path + ": " + sp_error("no descriptor"));
    }
    port->latency_timer_set_ = set_latency_timer(path);
  }
  // Exclusive use: TIOCEXCL refuses further opens (except by root); the flock also stops root
  // processes that follow the same convention (stride, minicom, ...).
  (void)ioctl(port->fd_, TIOCEXCL);
  if (flock(port->fd_, LOCK_EX | LOCK_NB) != 0) {
    return Status::error("serial port " + path + ": in use by another process");
  }
  port->discard_input();
  out = std::move(port);
  return {};
}

SerialPort::~SerialPort() {
  if (port_ != nullptr) {
    sp_close(port_);
    sp_free_port(port_);
  } else if (fd_ >= 0) {
    ::close(fd_);
  }
}

bool SerialPort::write(std::span<const std::uint8_t> bytes, std::int64_t deadline_ns) noexcept {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) return false;
    const std::int64_t left = deadline_ns - monotonic_ns();
    if (left <= 0) return false;
    pollfd pfd{fd_, POLLOUT, 0};
    const timespec ts{static_cast<time_t>(left / 1'000'000'000LL),
                      static_cast<long>(left % 1'000'000'000LL)};
    if (ppoll(&pfd, 1, &ts, nullptr) < 0 && errno != EINTR) return false;
  }
  return true;
}

std::ptrdiff_t SerialPort::read_some(std::span<std::uint8_t> out,
                                     std::int64_t deadline_ns) noexcept {
  for (;;) {
    const ssize_t n = ::read(fd_, out.data(), out.size());
    if (n > 0) return n;
    if (n < 0 && errno != EAGAIN && errno != EINTR) return -1;
    const std::int64_t left = deadline_ns - monotonic_ns();
    if (left <= 0) return 0;
    pollfd pfd{fd_, POLLIN, 0};
    const timespec ts{static_cast<time_t>(left / 1'000'000'000LL),
                      static_cast<long>(left % 1'000'000'000LL)};
    const int r = ppoll(&pfd, 1, &ts, nullptr);
    if (r < 0 && errno != EINTR) return -1;
    if (r > 0 && (pfd.revents & (POLLERR | POLLNVAL)) != 0) return -1;
    // POLLHUP on a pty slave means the master side is gone: wait out the deadline quietly
    // (reads then return 0/EIO); report as an error so callers can tell.
    if (r > 0 && (pfd.revents & POLLIN) == 0 && (pfd.revents & POLLHUP) != 0) return -1;
  }
}

void SerialPort::discard_input() noexcept {
  (void)tcflush(fd_, TCIFLUSH);
}

}  // namespace stride::hal::dxl
