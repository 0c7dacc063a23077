#include "twister/hal/expected.hpp"

#include <gtest/gtest.h>

#include <string>

namespace twister::hal {
namespace {

Expected<int> parse_port(const std::string& text) {
  if (text.empty()) return make_error(StatusCode::invalid_argument, "empty port");
  return std::stoi(text);
}

TEST(Expected, HoldsAValueOrAnError) {
  const Expected<int> good = parse_port("80");
  ASSERT_TRUE(good.has_value());
  EXPECT_EQ(*good, 80);
  const Expected<int> bad = parse_port("");
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().status.code(), StatusCode::invalid_argument);
  EXPECT_EQ(bad.error().message, "empty port");
}

TEST(Expected, VoidIsSuccessOrAnError) {
  const Expected<void> ok;
  EXPECT_TRUE(ok.has_value());
  const Expected<void> failed = make_error(StatusCode::io_error, "disk full");
  ASSERT_FALSE(failed);
  EXPECT_EQ(failed.error().message, "disk full");
}

}  // namespace
}  // namespace twister::hal
