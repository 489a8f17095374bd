// Reading JSON files and JSON Lines logs (json_file.hpp): open, parse, one line naming the file.
#include "stride/core/json_file.hpp"

#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

namespace stride::core {

Status read_text_file(const std::filesystem::path& path, std::string& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::error(path.string() + ": cannot open for reading");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) return Status::error(path.string() + ": cannot open for reading");
  out = std::move(text);
  return Status::ok();
}

Status parse_json_text(const std::string& text, const std::string& where, nlohmann::json& out) {
  try {
    out = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    return Status::error(where + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  return Status::ok();
}

Status read_json_file(const std::filesystem::path& path, nlohmann::json& out, JsonFileError* why) {
  std::string text;
  if (Status s = read_text_file(path, text); !s) {
    if (why != nullptr) *why = JsonFileError::kCannotOpen;
    return s;
  }
  if (Status s = parse_json_text(text, path.string(), out); !s) {
    if (why != nullptr) *why = JsonFileError::kNotJson;
    return s;
  }
  if (why != nullptr) *why = JsonFileError::kNone;
  return Status::ok();
}

Status read_json_lines(const std::filesystem::path& path, std::vector<nlohmann::json>& out,
                       JsonLinesDamage* damage) {
  std::ifstream in(path);
  if (!in) return Status::error(path.string() + ": cannot open for reading");
  JsonLinesDamage seen;
  for (std::string line; std::getline(in, line);) {
    ++seen.lines;
    if (line.empty()) continue;
    nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
      if (seen.damaged++ == 0) seen.first_line = seen.lines;
      continue;
    }
    out.push_back(std::move(j));
  }
  if (damage != nullptr) *damage = seen;
  return Status::ok();
}

}  // namespace stride::core
