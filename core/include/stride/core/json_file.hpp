// Reading JSON: the one place where a file is opened and read as JSON, or as JSON Lines, so that
// every parameter file, table, world file, config, robot description, run record and log fails
// the same way, with one line naming the file and what was wrong.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "stride/core/status.hpp"

namespace stride::core {

/// Why read_json_file failed, for callers that word the two cases their own way.
enum class JsonFileError { kNone, kCannotOpen, kNotJson };

/// Reads the whole file at `path` as bytes. Error: "PATH: cannot open for reading". `out` is
/// changed only on success. For a reader that needs the text itself (a content hash) as well
/// as its JSON: read_text_file, then parse_json_text.
Status read_text_file(const std::filesystem::path& path, std::string& out);

/// Parses `text` strictly (nothing but white space after the value). Error: "WHERE: not valid
/// JSON (PARSER'S MESSAGE)" on one line. `out` is changed only on success.
Status parse_json_text(const std::string& text, const std::string& where, nlohmann::json& out);

/// read_text_file, then parse_json_text naming the file. `why`, if given, says which error it
/// was.
Status read_json_file(const std::filesystem::path& path, nlohmann::json& out,
                      JsonFileError* why = nullptr);

/// What read_json_lines skipped: lines that are not a JSON object (a log cut by a kill).
struct JsonLinesDamage {
  std::size_t lines = 0;       ///< lines read, empty ones included
  std::size_t damaged = 0;     ///< lines skipped
  std::size_t first_line = 0;  ///< 1-based number of the first skipped line (0: none)
};

/// Reads a JSON Lines file (one object per line, as the run and calibration logs are written):
/// every line that parses as an object is appended to `out`, in order; empty lines are
/// ignored; any other line is counted in `damage` and skipped, since an append-only log cut by
/// a kill ends in a partial line. Error (nothing appended): "PATH: cannot open for reading".
Status read_json_lines(const std::filesystem::path& path, std::vector<nlohmann::json>& out,
                       JsonLinesDamage* damage = nullptr);

}  // namespace stride::core
