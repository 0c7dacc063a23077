// The Liberty family's start-up text (liberty_startup.hpp, docs/liberty-protocol.md §9),
// byte for byte as the public drivers send it (label devices).
#include "twister/tracker/liberty_startup.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace twister::tracker {
namespace {

std::string ladder(LibertyModel family, int rung) {
  std::array<char, 8> out{};
  return std::string(out.data(), liberty_ladder(family, rung, out));
}

std::string filter(char letter, const FilterSetting& s) {
  std::array<char, kMaxCommandBytes> out{};
  const auto n = encode_liberty_filter(letter, s, out);
  EXPECT_TRUE(n.ok());
  return std::string(out.data(), n.ok() ? *n : 0);
}

TEST(LibertyStartup, LadderAsVrpnSendsIt) {
  // VRPN's Liberty driver: CR F0 CR, ^Y CR after a few tries, then P; its LibertyHS
  // driver the same without the first CR.
  EXPECT_EQ(ladder(LibertyModel::liberty, 1), "\rF0\rP");
  EXPECT_EQ(ladder(LibertyModel::patriot, 2), "\rF0\rP");
  EXPECT_EQ(ladder(LibertyModel::liberty, 3), "\rF0\r\x19\rP");
  EXPECT_EQ(ladder(LibertyModel::latus, 1), "F0\rP");
  EXPECT_EQ(ladder(LibertyModel::latus, 3), "F0\r\x19\rP");
  std::array<char, 3> small{};  // a short buffer takes what fits
  EXPECT_EQ(liberty_ladder(LibertyModel::liberty, 3, small), 3u);
}

TEST(LibertyStartup, FiltersUnderTheLibertysLetters) {
  FilterSetting s;
  EXPECT_EQ(filter(kLibertyPositionFilter, s), "");  // leave: nothing sent
  s.mode = FilterSetting::Mode::off;
  EXPECT_EQ(filter(kLibertyPositionFilter, s), "X0,1,0,0\r");  // VRPN's "off"
  s.mode = FilterSetting::Mode::set;
  EXPECT_EQ(filter(kLibertyAttitudeFilter, s), "Y0.200,0.200,0.800,0.950\r");
  std::array<char, 4> small{};
  EXPECT_EQ(encode_liberty_filter(kLibertyPositionFilter, s, small).status().code(),
            StatusCode::resource_exhausted);
}

TEST(LibertyStartup, CommandTexts) {
  EXPECT_EQ(kLibertyWhoAmI, "\x16\r");
  EXPECT_EQ(kLibertyBinary, "F1\r");
  EXPECT_EQ(kLibertyCentimetres, "U1\r");
  EXPECT_EQ(kLibertyInches, "U0\r");
  EXPECT_EQ(kLibertyStartContinuous, "C\r");
  EXPECT_EQ(kLatusUsbBufferingOff, "@B0\r");
}

}  // namespace
}  // namespace twister::tracker
