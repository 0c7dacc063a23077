#include "allocation_counter.hpp"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <memory>
#include <numeric>
#include <vector>

namespace {

TEST(AllocationCounter, CountsOperatorNew) {
  twister::test::AllocationCounter counter;
  auto p = std::make_unique<int>(3);
  int* volatile keep = p.get();  // the compiler may not elide an allocation it must expose
  (void)keep;
  EXPECT_GE(counter.count(), 1u);
}

TEST(AllocationCounter, CountsMalloc) {
  twister::test::AllocationCounter counter;
  void* volatile p = std::malloc(64);
  EXPECT_GE(counter.count(), 1u);
  std::free(p);
}

TEST(AllocationCounter, StackWorkIsNotCounted) {
  std::array<int, 64> values{};
  EXPECT_NO_ALLOCATIONS(std::iota(values.begin(), values.end(), 0));
  EXPECT_EQ(values[63], 63);
}

// The guard must fail a test whose guarded scope allocates.
TEST(AllocationCounter, GuardFailsWhenScopeAllocates) {
  EXPECT_NONFATAL_FAILURE(EXPECT_NO_ALLOCATIONS(std::vector<int> v(100); v[0] = 1),
                          "heap allocation inside a no-allocation scope");
}

}  // namespace
