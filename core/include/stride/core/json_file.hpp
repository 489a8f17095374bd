// Reading a JSON file: the one place where a file is opened and parsed as JSON, so that every
// parameter file, table, world file, config and run record fails the same way, with one line
// naming the file and what was wrong.
#pragma once

#include <filesystem>

#include <nlohmann/json_fwd.hpp>

#include "stride/core/status.hpp"

namespace stride::core {

/// Why read_json_file failed, for callers that word the two cases their own way.
enum class JsonFileError { kNone, kCannotOpen, kNotJson };

/// Reads and parses the whole file at `path` (strictly: nothing but white space after the
/// value). Errors: "PATH: cannot open for reading" and "PATH: not valid JSON (PARSER'S
/// MESSAGE)". `out` is changed only on success; `why`, if given, says which error it was.
Status read_json_file(const std::filesystem::path& path, nlohmann::json& out,
                      JsonFileError* why = nullptr);

}  // namespace stride::core
