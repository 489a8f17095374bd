// PseudoTerminal and PtyBridge implementation (posix_openpt; where /dev/ptmx belongs to
// another devpts instance than /dev/pts, as in some containers, /dev/pts/ptmx instead).
#include "pseudo_terminal.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <stdexcept>

namespace stride::test {

PseudoTerminal::PseudoTerminal() {
  for (int attempt = 0; attempt < 2 && master_ < 0; ++attempt) {
    const int fd = attempt == 0 ? ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC)
                                : ::open("/dev/pts/ptmx", O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) continue;
    char name[128];
    struct stat st {};
    if (::grantpt(fd) != 0 || ::unlockpt(fd) != 0 || ::ptsname_r(fd, name, sizeof name) != 0 ||
        ::stat(name, &st) != 0) {
      ::close(fd);
      continue;
    }
    master_ = fd;
    slave_path_ = name;
  }
  if (master_ < 0) throw std::runtime_error("cannot open a pseudo-terminal");
  termios raw{};
  if (::tcgetattr(master_, &raw) == 0) {
    ::cfmakeraw(&raw);
    (void)::tcsetattr(master_, TCSANOW, &raw);
  }
  (void)::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
}

PseudoTerminal::~PseudoTerminal() {
  close_master();
}

void PseudoTerminal::close_master() {
  if (master_ >= 0) ::close(master_);
  master_ = -1;
}

bool PseudoTerminal::write(std::string_view bytes) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!bytes.empty()) {
    const ssize_t n = ::write(master_, bytes.data(), bytes.size());
    if (n > 0) {
      bytes.remove_prefix(static_cast<std::size_t>(n));
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) return false;
    if (std::chrono::steady_clock::now() > deadline) return false;
    pollfd p{master_, POLLOUT, 0};
    (void)::poll(&p, 1, 10);
  }
  return true;
}

bool PseudoTerminal::read_for(std::string& out, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  char buffer[4096];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return true;
    pollfd p{master_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
    const ssize_t n = ::read(master_, buffer, sizeof buffer);
    if (n > 0) {
      out.append(buffer, static_cast<std::size_t>(n));
      return true;
    }
    if (n < 0 && errno == EAGAIN) continue;
    if (n < 0 && errno == EIO) {  // no slave open (yet or any more): wait
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      continue;
    }
    return false;
  }
}

bool PseudoTerminal::read_until(std::string& received,
                                const std::function<bool(const std::string&)>& done,
                                std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done(received)) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    if (!read_for(received, std::min(left, std::chrono::milliseconds(50)))) return false;
  }
  return true;
}

std::string final_line_of(const std::string& text) {
  std::size_t start = 0;
  std::string found;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // only complete lines count
    std::string line = text.substr(start, end - start);
    while (!line.empty() && line.back() == '\r') line.pop_back();
    while (line.rfind("> ", 0) == 0) line.erase(0, 2);
    if (line == "ok" || line.rfind("ok ", 0) == 0 || line.rfind("err ", 0) == 0) found = line;
    start = end + 1;
  }
  return found;
}

std::string PseudoTerminal::command(std::string_view line, std::chrono::milliseconds timeout) {
  std::string received;
  if (!write(std::string(line) + "\r")) return {};
  if (!read_until(
          received, [](const std::string& r) { return !final_line_of(r).empty(); }, timeout)) {
    return {};
  }
  return received;
}

PtyBridge::PtyBridge() {
  relay_ = std::thread([this] {
    char buffer[4096];
    while (!stop_.load()) {
      pollfd p[2] = {{a_.master_fd(), POLLIN, 0}, {b_.master_fd(), POLLIN, 0}};
      if (::poll(p, 2, 20) <= 0) continue;
      for (int i = 0; i < 2; ++i) {
        if ((p[i].revents & POLLIN) == 0) {
          if ((p[i].revents & (POLLHUP | POLLERR)) != 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(5));  // no slave open yet
          }
          continue;
        }
        const ssize_t n = ::read(p[i].fd, buffer, sizeof buffer);
        if (n > 0)
          (void)(i == 0 ? b_ : a_).write(std::string_view(buffer, static_cast<std::size_t>(n)));
      }
    }
  });
}

PtyBridge::~PtyBridge() {
  stop_ = true;
  if (relay_.joinable()) relay_.join();
}

}  // namespace stride::test
