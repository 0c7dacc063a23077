// [exhibit] (issue 25): defaults, a full section into the station's exhibit mode, and
// the refusals (no archive_dir, a chord on a grab or move line, an existing chord, a
// line that does not exist, values out of range). Label exhibit.
#include <gtest/gtest.h>

#include <string>

#include "config/station_config.hpp"
#include "config_test_support.hpp"
#include "station_setup.hpp"

namespace twister::station_app {
namespace {

using test::messages;

const std::string kBase = test::kSixButtonStation;  // no [sculpt.buttons]

ConfigParseResult parse_exhibit(const std::string& exhibit, const std::string& more = "") {
  return parse_station_config(kBase + more + "[exhibit]\n" + exhibit, "t.toml");
}

TEST(ExhibitConfig, OffByDefaultAndAFullSectionReachesTheStation) {
  const auto none = parse_station_config(kBase, "t.toml");
  ASSERT_TRUE(none.ok()) << messages(none);
  EXPECT_FALSE(none.config.exhibit.enabled);
  auto off = make_station_setup(none.config);
  ASSERT_TRUE(off.has_value());
  EXPECT_FALSE(off->exhibit.visitor.enabled);
  const auto r = parse_exhibit(
      "enabled = true\narchive_dir = \"/var/lib/twister/archive\"\nidle_seconds = 45\n"
      "grace_seconds = 4.5\nnew_sculpture_chord = [1, 5]\nchord_hold_seconds = 2\n"
      "motion_threshold_m = 0.03\nretry_seconds = 10\nkeep_archives = 100\n"
      "keep_archive_mb = 512\n");
  ASSERT_TRUE(r.ok()) << messages(r);
  auto setup = make_station_setup(r.config);
  ASSERT_TRUE(setup.has_value());
  const station::ExhibitConfig& x = setup->exhibit;
  EXPECT_TRUE(x.visitor.enabled);
  EXPECT_EQ(x.visitor.idle_us, 45'000'000);
  EXPECT_EQ(x.visitor.grace_us, 4'500'000);
  EXPECT_EQ(x.visitor.chord_hold_us, 2'000'000);
  EXPECT_EQ(x.visitor.retry_us, 10'000'000);
  EXPECT_DOUBLE_EQ(x.visitor.motion_threshold_m, 0.03);
  EXPECT_EQ(x.chord_lines, (1u << 1) | (1u << 5));
  EXPECT_EQ(r.config.exhibit.keep_archives, 100u);
  EXPECT_EQ(r.config.exhibit.keep_archive_mb, 512u);
}

TEST(ExhibitConfig, BadValuesAndCollidingChordsAreRefusedWithTheKey) {
  const auto expect_error = [](const ConfigParseResult& r, const std::string& text) {
    EXPECT_FALSE(r.ok());
    EXPECT_NE(messages(r).find(text), std::string::npos) << messages(r);
  };
  expect_error(parse_exhibit("enabled = true\n"), "exhibit.archive_dir");
  expect_error(parse_exhibit("new_sculpture_chord = [0, 5]\n"), "line 0 grabs or moves");
  expect_error(parse_exhibit("new_sculpture_chord = [2, 4]\n"), "line 2 grabs or moves");
  expect_error(parse_exhibit("new_sculpture_chord = [1, 9]\n"), "line 9 does not exist");
  expect_error(parse_exhibit("new_sculpture_chord = [1]\n"), "exhibit.new_sculpture_chord");
  expect_error(parse_exhibit("new_sculpture_chord = [1, 1]\n"), "exhibit.new_sculpture_chord");
  expect_error(parse_exhibit("new_sculpture_chord = [4, 1]\n",
                             "[sculpt.buttons.left]\ngrab = 0\nundo = [1, 4]\n"),
               "already a [sculpt.buttons] chord");
  expect_error(parse_exhibit("idle_seconds = 1\n"), "exhibit.idle_seconds");
  expect_error(parse_exhibit("keep_archives = 0\n"), "exhibit.keep_archives");
  expect_error(parse_exhibit("idle = 5\n"), "exhibit.idle");  // unknown key
}

}  // namespace
}  // namespace twister::station_app
