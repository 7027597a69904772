// test_pool_starved.cpp - learner.pool_starved: ParallelFor (learner/src/parallel.hpp) when no
// memory is left to make a thread: the pass runs on the threads there are, every task once,
// and nothing is thrown. A binary of its own, because it replaces the global allocation
// functions (the sanitizer build's new/delete mismatch checks stay on for every other test).
#include <cstdlib>
#include <functional>
#include <new>
#include <vector>

#include "parallel.hpp"

// cmocka last: its fail() macro would clash with the standard library.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
extern "C" {
#include <cmocka.h>
}

// While a thread's count is above 0, its allocations throw std::bad_alloc (each one counts it
// down). Every unaligned form is replaced, as a set over malloc and free, so that no pair mixes
// this allocator with the runtime's (the aligned forms stay the runtime's, a pair of their own).
static thread_local int failing_allocations = 0;

static void* Allocate(std::size_t size) {
  if (failing_allocations > 0) {
    --failing_allocations;
    throw std::bad_alloc();
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

static void* AllocateOrNull(std::size_t size) noexcept {
  try {
    return Allocate(size);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}

// GCC, seeing new-expressions inlined elsewhere, would take free() here for a mismatch.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t size) { return Allocate(size); }
void* operator new[](std::size_t size) { return Allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return AllocateOrNull(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return AllocateOrNull(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

using gmmrrt::learn::detail::ParallelFor;

// A pass started from inside a pool task makes its own threads (the pool is busy); with every
// allocation failing it can make none, and runs all its tasks on the caller.
static void test_no_memory_for_a_thread_runs_the_pass_on_the_caller(void** state) {
  (void)state;
  std::vector<int> hits(40, 0);
  bool threw = false;
  const std::function<void(long)> count = [&hits](long u) { ++hits[static_cast<size_t>(u)]; };
  ParallelFor(2, 2, [&](long t) {
    if (t != 0) return;
    failing_allocations = 8;
    try {
      ParallelFor(3, 40, count);
    } catch (const std::bad_alloc&) {
      threw = true;
    }
    failing_allocations = 0;
  });
  assert_false(threw);
  for (int h : hits) assert_int_equal(h, 1);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_no_memory_for_a_thread_runs_the_pass_on_the_caller),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
