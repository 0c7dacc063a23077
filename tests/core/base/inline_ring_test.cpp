#include "twister/base/inline_ring.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cstdint>
#include <deque>
#include <vector>

#include "allocation_counter.hpp"

namespace twister {
namespace {

template <typename Ring>
std::vector<int> contents(const Ring& ring) {
  return {ring.begin(), ring.end()};
}

TEST(InlineRing, PushRefusesWhenFull) {
  InlineRing<int, 3> r;
  EXPECT_TRUE(r.empty());
  EXPECT_EQ(r.capacity(), 3u);
  EXPECT_TRUE(r.push(1).ok());
  EXPECT_TRUE(r.push(2).ok());
  EXPECT_TRUE(r.push(3).ok());
  EXPECT_TRUE(r.full());
  EXPECT_EQ(r.push(4).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(contents(r), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(r.front(), 1);
  EXPECT_EQ(r.back(), 3);
}

TEST(InlineRing, PopFrontWrapsAround) {
  InlineRing<int, 3> r;
  for (int i = 0; i < 10; ++i) {
    ASSERT_TRUE(r.push(i).ok());
    if (r.size() == 2) r.pop_front();
  }
  EXPECT_EQ(contents(r), (std::vector<int>{9}));
  ASSERT_TRUE(r.push(10).ok());
  ASSERT_TRUE(r.push(11).ok());
  EXPECT_EQ(r[0], 9);
  EXPECT_EQ(r[1], 10);
  EXPECT_EQ(r[2], 11);
}

TEST(InlineRing, PushOverwriteDropsTheOldest) {
  InlineRing<int, 3> r;
  EXPECT_FALSE(r.push_overwrite(1));
  EXPECT_FALSE(r.push_overwrite(2));
  EXPECT_FALSE(r.push_overwrite(3));
  EXPECT_TRUE(r.push_overwrite(4));
  EXPECT_TRUE(r.push_overwrite(5));
  EXPECT_EQ(contents(r), (std::vector<int>{3, 4, 5}));
}

TEST(InlineRing, PopFrontIntoTakesTheOldestInOrder) {
  InlineRing<int, 4> r;
  for (int i = 0; i < 6; ++i) r.push_overwrite(i);  // 2 3 4 5, head mid-array
  std::array<int, 3> out{};
  EXPECT_EQ(r.pop_front_into(out), 3u);
  EXPECT_EQ(out, (std::array<int, 3>{2, 3, 4}));
  EXPECT_EQ(r.pop_front_into(out), 1u);
  EXPECT_EQ(out[0], 5);
  EXPECT_TRUE(r.empty());
  EXPECT_EQ(r.pop_front_into(out), 0u);
}

TEST(InlineRing, ClearAndDropFront) {
  InlineRing<int, 4> r;
  for (int i = 0; i < 4; ++i) r.push(i).ignore();
  r.drop_front(3);
  EXPECT_EQ(contents(r), (std::vector<int>{3}));
  r.clear();
  EXPECT_TRUE(r.empty());
  EXPECT_TRUE(r.push(7).ok());
  EXPECT_EQ(r.front(), 7);
}

TEST(SpanRing, RunsOverTheCallersSlots) {
  std::array<int, 2> slots{};
  SpanRing<int> r(slots);
  EXPECT_EQ(r.capacity(), 2u);
  EXPECT_TRUE(r.push(5).ok());
  EXPECT_TRUE(r.push(6).ok());
  EXPECT_EQ(r.push(7).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(slots, (std::array<int, 2>{5, 6}));
  SpanRing<int> none;
  EXPECT_EQ(none.push(1).code(), StatusCode::resource_exhausted);
  EXPECT_TRUE(none.push_overwrite(1));
  EXPECT_TRUE(none.empty());
}

constexpr int constant_ring() {
  InlineRing<int, 2> r;
  r.push(1).ignore();
  r.push(2).ignore();
  r.pop_front();
  r.push(3).ignore();
  return r[0] * 10 + r[1];
}
static_assert(constant_ring() == 23);

TEST(InlineRing, HotOperationsDoNotAllocate) {
  InlineRing<std::uint64_t, 32> r;
  std::array<std::uint64_t, 8> out{};
  EXPECT_NO_ALLOCATIONS({
    for (std::uint64_t i = 0; i < 100; ++i) {
      r.push_overwrite(i);
      if (i % 3 == 0) r.pop_front();
    }
    r.pop_front_into(out);
    for (const std::uint64_t x : r) out[0] += x;
    r.clear();
  });
}

static_assert(internal::kDebugChecks, "compiled with the bounds checks on (CMakeLists.txt)");

TEST(InlineRingDeathTest, ReadingWhatIsNotThereStopsDebugBuilds) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  InlineRing<int, 4> r;
  EXPECT_DEATH(r.pop_front(), "");
  EXPECT_DEATH((void)r.front(), "");
  r.push(1).ignore();
  EXPECT_DEATH((void)r[1], "");
  EXPECT_DEATH(r.drop_front(2), "");
}

// The same operations on a ring and on a std::deque (a bounded queue, refusing or
// dropping the oldest when full) leave the same elements in the same order.
RC_GTEST_PROP(InlineRingProperty, BehavesAsABoundedStdDeque, ()) {
  constexpr std::size_t kCap = 5;
  InlineRing<int, kCap> r;
  std::array<int, kCap> slots{};
  SpanRing<int> s(slots);
  std::deque<int> model;
  const auto ops =
      *rc::gen::container<std::vector<std::uint8_t>>(rc::gen::inRange<std::uint8_t>(0, 5));
  int next = 0;
  for (const std::uint8_t op : ops) {
    if (op == 0) {
      const bool fits = model.size() < kCap;
      RC_ASSERT(r.push(next).ok() == fits);
      RC_ASSERT(s.push(next).ok() == fits);
      if (fits) model.push_back(next);
    } else if (op == 1) {
      const bool drops = model.size() == kCap;
      RC_ASSERT(r.push_overwrite(next) == drops);
      RC_ASSERT(s.push_overwrite(next) == drops);
      if (drops) model.pop_front();
      model.push_back(next);
    } else if (op == 2 && !model.empty()) {
      r.pop_front();
      s.pop_front();
      model.pop_front();
    } else if (op == 3) {
      std::array<int, 2> out{};
      const std::size_t n = r.pop_front_into(out);
      s.drop_front(n);
      RC_ASSERT(n == std::min<std::size_t>(2, model.size()));
      for (std::size_t i = 0; i < n; ++i) {
        RC_ASSERT(out[i] == model.front());
        model.pop_front();
      }
    }
    ++next;
    RC_ASSERT(r.size() == model.size());
    RC_ASSERT(contents(r) == std::vector<int>(model.begin(), model.end()));
    RC_ASSERT(contents(s) == std::vector<int>(model.begin(), model.end()));
    if (!model.empty()) RC_ASSERT(r.back() == model.back());
  }
}

}  // namespace
}  // namespace twister
