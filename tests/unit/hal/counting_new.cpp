// Replacement global operator new/delete that count allocations (see counting_new.hpp).
#include "counting_new.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<bool> g_count_new{false};
std::atomic<std::size_t> g_new_calls{0};
}  // namespace

namespace stride::hal::test {
void begin_counting_new() {
  g_new_calls = 0;
  g_count_new = true;
}
std::size_t end_counting_new() {
  g_count_new = false;
  return g_new_calls.load();
}
}  // namespace stride::hal::test

void* operator new(std::size_t size) {
  if (g_count_new.load(std::memory_order_relaxed)) g_new_calls.fetch_add(1);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  return ::operator new(size);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
