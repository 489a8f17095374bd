// Line-oriented log files of a run directory: appending lines so that a killed process loses
// nothing already written (each line goes to the kernel with one write()), and cutting a log back
// to its first N complete lines (by atomic replace).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "stride/core/status.hpp"

namespace stride::opt {

class LineLog {
 public:
  LineLog() = default;
  ~LineLog();
  LineLog(const LineLog&) = delete;
  LineLog& operator=(const LineLog&) = delete;

  Status open(const std::filesystem::path& path);
  /// Appends `line` and a newline with a single write().
  Status append(const std::string& line);
  /// Flushes to the disk (before a checkpoint refers to these lines).
  Status sync();
  std::size_t lines() const { return lines_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::size_t lines_ = 0;
};

/// Reads the first `count` complete lines of `path` (an error if there are fewer) and rewrites
/// the file to hold exactly those lines. A missing file counts as empty.
Status keep_first_lines(const std::filesystem::path& path, std::size_t count,
                        std::vector<std::string>& lines);

}  // namespace stride::opt
