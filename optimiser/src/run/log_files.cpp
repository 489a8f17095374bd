// LineLog and keep_first_lines (see log_files.hpp).
#include "stride/optimiser/run/log_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "stride/core/atomic_file.hpp"

namespace stride::opt {

LineLog::~LineLog() {
  if (fd_ >= 0) ::close(fd_);
}

Status LineLog::open(const std::filesystem::path& path) {
  path_ = path;
  fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) return Status::error(path.string() + ": " + std::strerror(errno));
  std::ifstream in(path);
  std::string line;
  lines_ = 0;
  while (std::getline(in, line)) ++lines_;
  return {};
}

Status LineLog::append(const std::string& line) {
  const std::string text = line + "\n";
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return Status::error(path_.string() + ": " + std::strerror(errno));
    }
    done += static_cast<std::size_t>(n);
  }
  ++lines_;
  return {};
}

Status LineLog::sync() {
  if (::fdatasync(fd_) != 0) return Status::error(path_.string() + ": " + std::strerror(errno));
  return {};
}

Status keep_first_lines(const std::filesystem::path& path, std::size_t count,
                        std::vector<std::string>& lines) {
  lines.clear();
  std::string text;
  if (std::filesystem::exists(path)) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream buffer;
    buffer << in.rdbuf();
    text = buffer.str();
  }
  std::size_t pos = 0;
  while (lines.size() < count) {
    const std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) {
      return Status::error(path.string() + " holds " + std::to_string(lines.size()) +
                           " complete lines, the checkpoint needs " + std::to_string(count));
    }
    lines.push_back(text.substr(pos, end - pos));
    pos = end + 1;
  }
  if (pos == text.size() && std::filesystem::exists(path)) return {};
  return core::write_file_atomically(path, std::string_view(text).substr(0, pos));
}

}  // namespace stride::opt
