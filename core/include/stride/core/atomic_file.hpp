// Atomic file replacement: write a temporary file beside the target, flush it to disk, then
// rename it over the target, so a reader or a crash never sees a half-written file.
#pragma once

#include <filesystem>
#include <string_view>

#include "stride/core/status.hpp"

namespace stride::core {

/// Replaces `path` with `contents` atomically. The error names the file and the OS reason.
Status write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace stride::core
