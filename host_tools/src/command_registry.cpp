// Storage for the subcommand registry.
#include <algorithm>

#include "stride/host_tools/command.hpp"

namespace stride::tools {

namespace {
std::vector<Command>& registry() {
  static std::vector<Command> list;
  return list;
}
}  // namespace

const std::vector<Command>& commands() {
  auto& list = registry();
  std::sort(list.begin(), list.end(),
            [](const Command& a, const Command& b) { return a.name < b.name; });
  return list;
}

bool register_command(Command command) {
  registry().push_back(command);
  return true;
}

}  // namespace stride::tools
