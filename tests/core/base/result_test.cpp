#include "twister/base/result.hpp"

#include <gtest/gtest.h>

namespace twister {
namespace {

Result<int> half(int x) {
  if (x % 2 != 0) return StatusCode::invalid_argument;
  return x / 2;
}

Result<int> quarter(int x) {
  TWISTER_TRY_ASSIGN(const int h, half(x));
  return half(h);
}

Status check_even(int x) {
  TWISTER_TRY(half(x));
  return ok_status();
}

TEST(Result, HoldsValueOrStatus) {
  EXPECT_EQ(half(8).value(), 4);
  EXPECT_FALSE(half(3).ok());
  EXPECT_EQ(half(3).status().code(), StatusCode::invalid_argument);
  EXPECT_EQ(half(3).value_or(-1), -1);
}

TEST(Result, TryAssignPropagatesErrors) {
  EXPECT_EQ(quarter(8).value(), 2);
  EXPECT_EQ(quarter(6).status().code(), StatusCode::invalid_argument);
  EXPECT_TRUE(check_even(2).ok());
  EXPECT_EQ(check_even(1).code(), StatusCode::invalid_argument);
}

TEST(Status, NamesEveryCode) {
  EXPECT_STREQ(Status(StatusCode::data_loss).name(), "data_loss");
  EXPECT_STREQ(ok_status().name(), "ok");
}

}  // namespace
}  // namespace twister
