// The readable names of TaskValue's types (see task_value.hpp).
#include "stride/optimiser/tasks/task_value.hpp"

#include <cstdlib>
#include <memory>

#if defined(__GNUG__)
#include <cxxabi.h>
#endif

namespace stride::opt {

std::string task_value_type_name(const std::type_info& type) {
#if defined(__GNUG__)
  int status = 0;
  const std::unique_ptr<char, void (*)(void*)> name(
      abi::__cxa_demangle(type.name(), nullptr, nullptr, &status), std::free);
  if (status == 0 && name != nullptr) return name.get();
#endif
  return type.name();
}

}  // namespace stride::opt
