// Storage for the subcommand registry, and running one command (command.hpp).
#include <algorithm>
#include <exception>
#include <string>

#include "stride/host_tools/command.hpp"
#include "stride/host_tools/command_errors.hpp"

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

int run_command(const Command& command, int argc, char** argv) {
  const std::string name(command.name);
  const CommandErrors errors(name.c_str());
  try {
    return command.run(argc, argv);
  } catch (const std::exception& e) {
    return errors.failure(std::string("internal error: ") + e.what());
  } catch (...) {
    return errors.failure("internal error: an unknown exception");
  }
}

}  // namespace stride::tools
