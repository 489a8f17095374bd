// Child processes for end-to-end tests: start a built program with its output in files,
// wait for it, read the files.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace stride::test {

/// Starts `argv` (argv[0] a path) with stdout and stderr redirected to the given files.
/// Returns the pid, or -1 if it could not start.
pid_t spawn(const std::vector<std::string>& argv, const std::filesystem::path& out,
            const std::filesystem::path& err);
/// Waits for `pid`; returns its exit code, 128 + signal if killed, -1 on error.
int wait_exit(pid_t pid);
/// The whole contents of a file ("" if unreadable).
std::string slurp(const std::filesystem::path& path);

/// A finished child: its exit code (as wait_exit) and what it printed.
struct ChildRun {
  int code = -1;
  std::string out, err;
};
/// Runs `argv` to the end with its output in `dir`/out and `dir`/err, and reads them.
ChildRun run_child(const std::vector<std::string>& argv, const std::filesystem::path& dir);

}  // namespace stride::test
