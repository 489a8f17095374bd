// Counts global operator new calls while switched on (replacement operators in counting_new.cpp,
// linked into stride_unit_hal), to check that the HAL's per-tick calls allocate nothing.
#pragma once

#include <cstddef>

namespace stride::hal::test {

void begin_counting_new();
/// Stops counting; returns the operator new calls since begin_counting_new().
std::size_t end_counting_new();

}  // namespace stride::hal::test
