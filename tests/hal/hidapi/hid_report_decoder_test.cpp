#include "twister/hal/hid_report_decoder.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "support/allocation_counter.hpp"

namespace twister::hal {
namespace {

TEST(HidReportDecoderTest, MapsBitsToEdgesOnlyOnChange) {
  HidReportDecoder d;
  const std::array<HidButtonBitMap, 3> map{{{1, 0x04}, {1, 0x08}, {2, 0x01}}};
  ASSERT_TRUE(d.configure(map).ok());
  HidReportDecoder::Edges out;
  std::array<std::uint8_t, 3> report{0x00, 0x04, 0x00};
  out = d.decode(report, 100);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].line, 0);
  EXPECT_TRUE(out[0].pressed);
  EXPECT_EQ(out[0].time_us, 100);
  EXPECT_EQ(d.decode(report, 200).size(), 0u);  // same report: no edge

  report = {0x00, 0x08 | 0xF0, 0x01};  // other bits in the byte are ignored
  out = d.decode(report, 300);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].line, 0);
  EXPECT_FALSE(out[0].pressed);
  EXPECT_EQ(out[1].line, 1);
  EXPECT_TRUE(out[1].pressed);
  EXPECT_EQ(out[2].line, 2);
  EXPECT_TRUE(out[2].pressed);
}

TEST(HidReportDecoderTest, ShortReportLeavesButtonsUnchanged) {
  HidReportDecoder d;
  const std::array<HidButtonBitMap, 2> map{{{0, 0x01}, {5, 0x01}}};
  ASSERT_TRUE(d.configure(map).ok());
  HidReportDecoder::Edges out;
  const std::array<std::uint8_t, 6> full{0x01, 0, 0, 0, 0, 0x01};
  out = d.decode(full, 1);
  ASSERT_EQ(out.size(), 2u);
  const std::array<std::uint8_t, 1> short_report{0x00};
  out = d.decode(short_report, 2);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].line, 0);
  EXPECT_FALSE(out[0].pressed);
}

TEST(HidReportDecoderTest, RejectsZeroMaskAndTooManyButtons) {
  HidReportDecoder d;
  const std::array<HidButtonBitMap, 1> zero{{{0, 0}}};
  EXPECT_EQ(d.configure(zero).code(), StatusCode::invalid_argument);
  std::array<HidButtonBitMap, 9> many{};
  for (auto& b : many) b = {0, 1};
  EXPECT_EQ(d.configure(many).code(), StatusCode::invalid_argument);
}

TEST(HidReportDecoderTest, DecodeDoesNotAllocate) {
  HidReportDecoder d;
  const std::array<HidButtonBitMap, 2> map{{{0, 0x01}, {0, 0x02}}};
  ASSERT_TRUE(d.configure(map).ok());
  HidReportDecoder::Edges out;
  std::array<std::uint8_t, 1> report{0x03};
  EXPECT_NO_ALLOCATIONS(out = d.decode(report, 1));
  EXPECT_EQ(out.size(), 2u);
}

}  // namespace
}  // namespace twister::hal
