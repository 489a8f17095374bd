// read_file: the whole contents of a file as a string ("" if it cannot be opened).
#pragma once

#include <filesystem>
#include <string>

namespace stride::test {

std::string read_file(const std::filesystem::path& path);

}  // namespace stride::test
