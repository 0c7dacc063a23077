// Counts heap allocations made by this thread, for "no allocation after
// initialisation" tests. Linking twister_test_support replaces global operator new
// (and, outside sanitizer builds, malloc/calloc/realloc) with counting versions.
#pragma once

#include <cstddef>

namespace twister::test {

// Allocations made by the calling thread since the program started.
std::size_t thread_allocation_count();

// Counts the allocations of the calling thread while it is alive.
class AllocationCounter {
 public:
  AllocationCounter() : start_(thread_allocation_count()) {}
  std::size_t count() const { return thread_allocation_count() - start_; }

 private:
  std::size_t start_;
};

}  // namespace twister::test

// Fails the test (non-fatally) when `statement` allocates on the heap.
#define EXPECT_NO_ALLOCATIONS(statement)                                        \
  do {                                                                          \
    ::twister::test::AllocationCounter twister_alloc_counter_;                  \
    statement;                                                                  \
    const std::size_t twister_allocs_ = twister_alloc_counter_.count();         \
    EXPECT_EQ(twister_allocs_, 0u) << "heap allocation inside a no-allocation " \
                                      "scope: " #statement;                     \
  } while (0)
