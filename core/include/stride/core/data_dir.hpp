// The directory a program's data files come from (configuration, scripts, models).
//
// In order: the STRIDE_DATA_DIR environment variable when set; <prefix>/share/stride when the
// running binary is <prefix>/bin/<name> and `marker` (a path relative to that directory, e.g.
// "config/servo_table.json") exists there, wherever the prefix was copied to; else
// `source_tree`, the folder in the source tree a development build reads.
#pragma once

#include <filesystem>

namespace stride::core {

std::filesystem::path data_dir(const std::filesystem::path& marker,
                               const std::filesystem::path& source_tree);

}  // namespace stride::core
