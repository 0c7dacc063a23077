#include "twister/base/inline_vector.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "allocation_counter.hpp"

namespace twister {
namespace {

struct Item {
  int id = 0;
  float weight = 0.0F;
  friend bool operator==(const Item&, const Item&) = default;
};

TEST(InlineVector, StartsEmptyWithItsCapacity) {
  InlineVector<int, 4> v;
  EXPECT_TRUE(v.empty());
  EXPECT_FALSE(v.full());
  EXPECT_EQ(v.size(), 0u);
  EXPECT_EQ(v.capacity(), 4u);
  EXPECT_EQ(v.begin(), v.end());
  EXPECT_TRUE(v.span().empty());
}

TEST(InlineVector, PushBackRefusesWhenFullAndChangesNothing) {
  InlineVector<int, 3> v;
  EXPECT_TRUE(v.push_back(1).ok());
  EXPECT_TRUE(v.push_back(2).ok());
  EXPECT_TRUE(v.emplace_back(3).ok());
  EXPECT_TRUE(v.full());
  EXPECT_EQ(v.push_back(4).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(v.emplace_back(5).code(), StatusCode::resource_exhausted);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0], 1);
  EXPECT_EQ(v[2], 3);
  EXPECT_EQ(v.front(), 1);
  EXPECT_EQ(v.back(), 3);
}

TEST(InlineVector, EmplaceBuildsAggregates) {
  InlineVector<Item, 2> v;
  ASSERT_TRUE(v.emplace_back(7, 0.5F).ok());
  EXPECT_EQ(v.back(), (Item{7, 0.5F}));
}

TEST(InlineVector, PopBackAndClear) {
  InlineVector<int, 4> v{1, 2, 3};
  v.pop_back();
  EXPECT_EQ(v.size(), 2u);
  EXPECT_EQ(v.back(), 2);
  v.clear();
  EXPECT_TRUE(v.empty());
  EXPECT_TRUE(v.push_back(9).ok());
  EXPECT_EQ(v[0], 9);
}

TEST(InlineVector, SpanSeesTheElementsOnly) {
  InlineVector<int, 8> v{4, 5, 6};
  const std::span<const int> s = v;
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[2], 6);
  std::span<int> m = v;
  m[0] = 40;
  EXPECT_EQ(v[0], 40);
  int sum = 0;
  for (const int x : v) sum += x;
  EXPECT_EQ(sum, 40 + 5 + 6);
}

TEST(InlineVector, AppendAndAssignTakeWhatFits) {
  InlineVector<int, 4> v{1};
  const std::vector<int> more{2, 3};
  EXPECT_TRUE(v.append(more).ok());
  EXPECT_EQ(v, (InlineVector<int, 4>{1, 2, 3}));
  const std::vector<int> many{5, 6, 7, 8, 9};
  EXPECT_EQ(v.append(many).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(v, (InlineVector<int, 4>{1, 2, 3, 5}));
  EXPECT_EQ(v.assign(many).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(v, (InlineVector<int, 4>{5, 6, 7, 8}));
  EXPECT_TRUE(v.assign(more).ok());
  EXPECT_EQ(v, (InlineVector<int, 4>{2, 3}));
}

TEST(InlineVector, ResizeValueInitialisesNewElements) {
  InlineVector<int, 4> v{1, 2, 3};
  v.resize(1);
  v.resize(3);
  EXPECT_EQ(v, (InlineVector<int, 4>{1, 0, 0}));
}

TEST(InlineVector, EraseKeepsOrder) {
  InlineVector<int, 6> v{0, 1, 2, 3, 4, 5};
  auto next = v.erase(v.begin() + 1);
  EXPECT_EQ(*next, 2);
  EXPECT_EQ(v, (InlineVector<int, 6>{0, 2, 3, 4, 5}));
  next = v.erase(v.begin() + 1, v.begin() + 3);
  EXPECT_EQ(*next, 4);
  EXPECT_EQ(v, (InlineVector<int, 6>{0, 4, 5}));
  EXPECT_EQ(erase_if(v, [](int x) { return x % 2 == 0; }), 2u);
  EXPECT_EQ(v, (InlineVector<int, 6>{5}));
}

TEST(InlineVector, SizeMemberIsAsSmallAsTheCapacityAllows) {
  EXPECT_EQ(sizeof(InlineVector<std::uint8_t, 15>), 16u);
  EXPECT_LE(sizeof(InlineVector<std::uint16_t, 300>), 300u * 2u + 2u);
  EXPECT_EQ(sizeof(InlineVector<std::uint32_t, 4>), 4u * 4u + 4u);  // padding to 4
}

constexpr int constant_sum() {
  InlineVector<int, 4> v{1, 2};
  v.push_back(3).ignore();
  v.pop_back();
  v.push_back(10).ignore();
  int sum = 0;
  for (const int x : v) sum += x;
  return sum;
}
static_assert(constant_sum() == 13);

TEST(InlineVector, HotOperationsDoNotAllocate) {
  InlineVector<Item, 16> v;
  EXPECT_NO_ALLOCATIONS({
    for (int i = 0; i < 20; ++i) v.push_back(Item{i, 1.0F}).ignore();
    v.erase(v.begin());
    erase_if(v, [](const Item& it) { return it.id % 3 == 0; });
    v.pop_back();
    const std::span<const Item> s = v;
    (void)s;
    v.clear();
  });
}

// Out-of-range access is a broken invariant: it stops the program in debug builds
// and is not checked in release (where this test has nothing to check).
static_assert(internal::kDebugChecks, "compiled with the bounds checks on (CMakeLists.txt)");

TEST(InlineVectorDeathTest, OutOfRangeIndexStopsDebugBuilds) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  InlineVector<int, 4> v{1, 2};
  EXPECT_DEATH((void)v[2], "");
  EXPECT_DEATH(v.erase(v.begin() + 3), "");
  InlineVector<int, 4> empty;
  EXPECT_DEATH(empty.pop_back(), "");
  EXPECT_DEATH((void)empty.back(), "");
}

// The same operations on an InlineVector and on a std::vector (refusing pushes past
// the capacity) leave the same elements.
RC_GTEST_PROP(InlineVectorProperty, BehavesAsABoundedStdVector, ()) {
  constexpr std::size_t kCap = 12;
  InlineVector<int, kCap> v;
  std::vector<int> model;
  const auto ops =
      *rc::gen::container<std::vector<std::uint8_t>>(rc::gen::inRange<std::uint8_t>(0, 6));
  int next = 0;
  for (const std::uint8_t op : ops) {
    switch (op) {
      case 0:
      case 1: {
        const bool fits = model.size() < kCap;
        RC_ASSERT(v.push_back(next).ok() == fits);
        if (fits) model.push_back(next);
        ++next;
        break;
      }
      case 2:
        if (!model.empty()) {
          v.pop_back();
          model.pop_back();
        }
        break;
      case 3:
        if (!model.empty()) {
          const std::size_t i = static_cast<std::size_t>(next) % model.size();
          v.erase(v.begin() + static_cast<std::ptrdiff_t>(i));
          model.erase(model.begin() + static_cast<std::ptrdiff_t>(i));
        }
        break;
      case 4: {
        const auto odd = [](int x) { return x % 2 != 0; };
        const std::size_t removed = erase_if(v, odd);
        RC_ASSERT(removed == std::erase_if(model, odd));
        break;
      }
      default:
        if (next % 7 == 0) {
          v.clear();
          model.clear();
        }
        ++next;
        break;
    }
    RC_ASSERT(v.size() == model.size());
    RC_ASSERT(std::vector<int>(v.begin(), v.end()) == model);
  }
}

}  // namespace
}  // namespace twister
