// The whole contents of a file (see read_file.hpp).
#include "read_file.hpp"

#include <fstream>
#include <sstream>

namespace stride::test {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace stride::test
