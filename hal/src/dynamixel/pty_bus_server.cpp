// PtyBusServer implementation (see pty_bus_server.hpp).
#include "stride/hal/dynamixel/pty_bus_server.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <vector>

namespace stride::hal::dxl {

namespace {

// Opens a master whose slave is visible at the returned path.
int open_master(std::string& slave) {
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int fd = attempt == 0 ? posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC)
                                : ::open("/dev/pts/ptmx", O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) continue;
    if (grantpt(fd) != 0 || unlockpt(fd) != 0) {
      ::close(fd);
      continue;
    }
    std::array<char, 128> name{};
    if (ptsname_r(fd, name.data(), name.size()) != 0) {
      ::close(fd);
      continue;
    }
    struct stat st {};
    if (::stat(name.data(), &st) != 0) {  // the slave lives in another devpts instance
      ::close(fd);
      continue;
    }
    slave = name.data();
    return fd;
  }
  return -1;
}

}  // namespace

Status PtyBusServer::create(const std::string& link_path, std::unique_ptr<PtyBusServer>& out) {
  std::unique_ptr<PtyBusServer> server(new PtyBusServer());
  server->master_fd_ = open_master(server->slave_path_);
  if (server->master_fd_ < 0) {
    return Status::error(std::string("cannot open a pseudo-terminal: ") + std::strerror(errno));
  }
  server->slave_keepalive_fd_ = ::open(server->slave_path_.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (server->slave_keepalive_fd_ >= 0) {
    termios tio{};
    if (tcgetattr(server->slave_keepalive_fd_, &tio) == 0) {
      cfmakeraw(&tio);
      (void)tcsetattr(server->slave_keepalive_fd_, TCSANOW, &tio);
    }
  }
  struct stat st {};
  if (::lstat(link_path.c_str(), &st) == 0) {
    if (!S_ISLNK(st.st_mode)) {
      return Status::error(link_path + " exists and is not a symlink");
    }
    ::unlink(link_path.c_str());
  }
  if (::symlink(server->slave_path_.c_str(), link_path.c_str()) != 0) {
    return Status::error("cannot create link " + link_path + ": " + std::strerror(errno));
  }
  server->link_path_ = link_path;
  out = std::move(server);
  return {};
}

PtyBusServer::~PtyBusServer() {
  if (!link_path_.empty()) ::unlink(link_path_.c_str());
  if (slave_keepalive_fd_ >= 0) ::close(slave_keepalive_fd_);
  if (master_fd_ >= 0) ::close(master_fd_);
}

Status PtyBusServer::serve(BusResponder& bus, const std::atomic<bool>& stop) {
  std::array<std::uint8_t, 4096> in{};
  std::vector<std::uint8_t> out;
  out.reserve(8192);
  while (!stop.load()) {
    pollfd pfd{master_fd_, POLLIN, 0};
    const int r = ::poll(&pfd, 1, 50);
    if (r < 0) {
      if (errno == EINTR) continue;
      return Status::error(std::string("pseudo-terminal poll: ") + std::strerror(errno));
    }
    if (r == 0 || (pfd.revents & POLLIN) == 0) continue;
    const ssize_t n = ::read(master_fd_, in.data(), in.size());
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN || errno == EIO) continue;
      return Status::error(std::string("pseudo-terminal read: ") + std::strerror(errno));
    }
    out.clear();
    std::int64_t delay_us = 0;
    bus.receive(std::span<const std::uint8_t>(in.data(), static_cast<std::size_t>(n)), out,
                delay_us);
    if (out.empty()) continue;
    if (delay_us > 0) {
      timespec ts{static_cast<time_t>(delay_us / 1'000'000),
                  static_cast<long>(delay_us % 1'000'000) * 1000};
      while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
      }
    }
    std::size_t done = 0;
    while (done < out.size()) {
      const ssize_t w = ::write(master_fd_, out.data() + done, out.size() - done);
      if (w < 0) {
        if (errno == EINTR || errno == EAGAIN) continue;
        return Status::error(std::string("pseudo-terminal write: ") + std::strerror(errno));
      }
      done += static_cast<std::size_t>(w);
    }
  }
  return {};
}

}  // namespace stride::hal::dxl
