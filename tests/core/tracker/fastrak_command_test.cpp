// The Fastrak command codec (fastrak_command.hpp): the bytes of every command the
// session sends, byte for byte; what decode refuses; and the round trips: any command
// encodes and decodes to itself, and any bytes that decode encode back to themselves.
#include "twister/tracker/fastrak_command.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <string>

namespace twister::tracker {
namespace {

std::string encoded(const FastrakCommand& c) {
  std::array<char, kMaxCommandBytes> buf{};
  const auto n = encode(c, buf);
  EXPECT_TRUE(n.ok());
  return std::string(buf.data(), n.ok() ? *n : 0);
}

Result<FastrakCommand> decoded(const std::string& bytes) {
  return decode(std::span<const char>(bytes.data(), bytes.size()));
}

TEST(FastrakCommand, WhatTheSessionSendsByteForByte) {
  EXPECT_EQ(encoded(station_state_command(2, false)), "l2,0\r");
  EXPECT_EQ(encoded(station_state_command(1, true)), "l1,1\r");
  EXPECT_EQ(encoded(output_list_command(
                1, OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf}))),
            "O1,2,11,16,1\r");
  EXPECT_EQ(encoded(hemisphere_command(3, {0, 0, -1})), "H3,0,0,-1\r");
  EXPECT_EQ(encoded(stylus_mode_command(1, 0)), "e1,0\r");
  FilterSetting off;
  off.mode = FilterSetting::Mode::off;
  EXPECT_EQ(encoded(*filter_command(ParameterCommand::position_filter, off)), "x,1\r");
  FilterSetting medium;
  medium.mode = FilterSetting::Mode::set;
  EXPECT_EQ(encoded(*filter_command(ParameterCommand::attitude_filter, medium)),
            "v0.200,0.200,0.800,0.950\r");
  EXPECT_FALSE(filter_command(ParameterCommand::position_filter, FilterSetting{}).has_value());
  EXPECT_EQ(encoded(Mode{ModeCommand::status}), "S");
  EXPECT_EQ(encoded(Mode{ModeCommand::continuous}), "C");
  EXPECT_EQ(encoded(Mode{ModeCommand::reinitialise}), "\x19");
}

TEST(FastrakCommand, LongestOutputListFits) {
  OutputList list;
  for (std::size_t i = 0; i < kMaxItems; ++i) list.items[list.count++] = Item::quaternion_ext;
  const std::string bytes = encoded(output_list_command(4, list));
  EXPECT_EQ(bytes.size(), 2 + 32 * 3 + 1u);  // "O4", 32 x ",61", CR
  EXPECT_LE(bytes.size(), kMaxCommandBytes);
}

TEST(FastrakCommand, FieldsSplitAtCommas) {
  const auto c = decoded("Q1,,90,,\r");
  ASSERT_TRUE(c.ok());
  const auto& p = std::get<Parameters>(*c);
  EXPECT_EQ(p.command, ParameterCommand::envelope);
  ASSERT_EQ(p.field_count(), 5u);
  EXPECT_EQ(p.field(0), "1");
  EXPECT_EQ(p.field(1), "");
  EXPECT_EQ(p.field(2), "90");
  EXPECT_EQ(p.field(7), "");
  const auto readback = decoded("x\r");
  ASSERT_TRUE(readback.ok());
  EXPECT_EQ(std::get<Parameters>(*readback).field_count(), 1u);
}

TEST(FastrakCommand, DecodeRefusesWhatIsNotOneCommand) {
  EXPECT_EQ(decoded("").status().code(), StatusCode::invalid_argument);
  EXPECT_EQ(decoded("Z").status().code(), StatusCode::invalid_argument);     // unknown
  EXPECT_EQ(decoded("SS").status().code(), StatusCode::invalid_argument);    // after a mode
  EXPECT_EQ(decoded("O1,2").status().code(), StatusCode::invalid_argument);  // no CR
  EXPECT_EQ(decoded("O1\rO").status().code(), StatusCode::invalid_argument);
  EXPECT_EQ(decoded("O1\n2\r").status().code(), StatusCode::invalid_argument);
  EXPECT_EQ(decoded("O" + std::string(kMaxCommandText + 1, '1') + "\r").status().code(),
            StatusCode::resource_exhausted);
  EXPECT_TRUE(decoded("O" + std::string(kMaxCommandText, '1') + "\r").ok());
}

TEST(FastrakCommand, EncodeNeedsRoom) {
  std::array<char, 4> small{};
  EXPECT_EQ(encode(station_state_command(1, true), small).status().code(),
            StatusCode::resource_exhausted);
  EXPECT_EQ(encode(Mode{ModeCommand::poll}, std::span<char>()).status().code(),
            StatusCode::resource_exhausted);
}

constexpr char kModeLetters[] = {'P', 'C', 'c', 'F', 'f',  'U',  'u',  'S',
                                 'W', 'T', 'D', 'd', 0x19, 0x0B, 0x13, 0x11};
constexpr char kParameterLetters[] = {'O', 'l', 'H', 'A', 'R', 'B', 'b', 'G',
                                      'N', 'e', 'I', 'x', 'v', 'Q', 'X', 'o'};

rc::Gen<FastrakCommand> any_command() {
  const auto mode = rc::gen::map(rc::gen::elementOf(std::string(kModeLetters, 16)),
                                 [](char c) { return FastrakCommand{Mode{*mode_command(c)}}; });
  const auto text_char =
      rc::gen::suchThat(rc::gen::arbitrary<char>(), [](char c) { return c != '\r' && c != '\n'; });
  const auto parameters =
      rc::gen::map(rc::gen::pair(rc::gen::elementOf(std::string(kParameterLetters, 16)),
                                 rc::gen::container<std::string>(text_char)),
                   [](const std::pair<char, std::string>& lt) {
                     Parameters p;
                     p.command = *parameter_command(lt.first);
                     p.append(std::string_view(lt.second).substr(0, kMaxCommandText));
                     return FastrakCommand{p};
                   });
  return rc::gen::oneOf(mode, parameters);
}

RC_GTEST_PROP(FastrakCommand, AnyCommandRoundTrips, ()) {
  const FastrakCommand c = *any_command();
  const std::string bytes = encoded(c);
  const auto back = decoded(bytes);
  RC_ASSERT(back.ok());
  RC_ASSERT(*back == c);
  RC_ASSERT(letter(*back) == bytes[0]);
}

RC_GTEST_PROP(FastrakCommand, AnyBytesThatDecodeEncodeBack, (const std::string& bytes)) {
  const auto c = decoded(bytes);
  if (!c.ok()) return;
  RC_ASSERT(encoded(*c) == bytes);
}

RC_GTEST_PROP(FastrakCommand, BuiltCommandsDecodeToTheirFields, (int station, bool enabled)) {
  const auto c = decoded(encoded(station_state_command(station, enabled)));
  RC_ASSERT(c.ok());
  const auto& p = std::get<Parameters>(*c);
  RC_ASSERT(p.field(0) == std::to_string(station));
  RC_ASSERT(p.field(1) == (enabled ? "1" : "0"));
}

}  // namespace
}  // namespace twister::tracker
