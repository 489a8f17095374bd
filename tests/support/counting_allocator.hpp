// A global operator new replacement that counts allocations while counting is switched on.
// Defined in its own translation unit so the compiler cannot inline (and mis-pair) the
// replacement operators into test code. Part of stride_test_support, so every test binary
// allocates through it (counting is off unless a test switches it on).
#pragma once

#include <cstddef>

namespace stride::test {

void start_counting_allocations();
/// Stops counting and returns the number of operator new calls since the start.
std::size_t stop_counting_allocations();

}  // namespace stride::test
