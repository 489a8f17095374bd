// read_json_file (json_file.hpp): open, parse, and one line naming the file on failure.
#include "stride/core/json_file.hpp"

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace stride::core {

Status read_json_file(const std::filesystem::path& path, nlohmann::json& out, JsonFileError* why) {
  const auto fail = [&](JsonFileError error, const std::string& message) {
    if (why != nullptr) *why = error;
    return Status::error(path.string() + ": " + message);
  };
  std::ifstream in(path);
  if (!in) return fail(JsonFileError::kCannotOpen, "cannot open for reading");
  try {
    out = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    return fail(JsonFileError::kNotJson, "not valid JSON (" + std::string(e.what()) + ")");
  }
  if (why != nullptr) *why = JsonFileError::kNone;
  return Status::ok();
}

}  // namespace stride::core
