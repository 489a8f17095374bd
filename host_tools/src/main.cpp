// `stride`: the host tool. Dispatches to the registered subcommands.
#include <cstdio>
#include <cstring>
#include <string_view>

#include "stride/host_tools/command.hpp"

namespace {

void print_usage(std::FILE* out) {
  std::fprintf(out, "usage: stride <command> [options]   (stride <command> --help)\n\ncommands:\n");
  for (const auto& c : stride::tools::commands()) {
    std::fprintf(out, "  %-10.*s %.*s\n", static_cast<int>(c.name.size()), c.name.data(),
                 static_cast<int>(c.summary.size()), c.summary.data());
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    print_usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string_view name = argv[1];
  for (const auto& c : stride::tools::commands()) {
    if (c.name == name) return stride::tools::run_command(c, argc - 1, argv + 1);
  }
  std::fprintf(stderr, "stride: unknown command '%s' (see stride --help)\n", argv[1]);
  return 2;
}
