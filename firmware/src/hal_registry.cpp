// Storage for the HAL backend registry.
#include "stride/firmware/hal_registry.hpp"

#include <algorithm>

namespace stride::fw {

namespace {
std::vector<HalBackend>& registry() {
  static std::vector<HalBackend> list;
  return list;
}
}  // namespace

const std::vector<HalBackend>& hal_backends() {
  auto& list = registry();
  std::sort(list.begin(), list.end(),
            [](const HalBackend& a, const HalBackend& b) { return a.name < b.name; });
  return list;
}

bool register_hal_backend(HalBackend backend) {
  registry().push_back(backend);
  return true;
}

}  // namespace stride::fw
