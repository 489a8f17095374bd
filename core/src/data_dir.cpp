// data_dir: the environment, the installed prefix beside the binary, or the source tree.
#include "stride/core/data_dir.hpp"

#include <cstdlib>
#include <system_error>

namespace stride::core {

std::filesystem::path data_dir(const std::filesystem::path& marker,
                               const std::filesystem::path& source_tree) {
  if (const char* env = std::getenv("STRIDE_DATA_DIR"); env != nullptr && *env != '\0') return env;
  std::error_code error;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const auto installed = exe.parent_path().parent_path() / "share" / "stride";
    if (std::filesystem::exists(installed / marker, error)) return installed;
  }
  return source_tree;
}

}  // namespace stride::core
