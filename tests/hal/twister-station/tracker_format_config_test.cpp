// Issue 23: [tracker] format = "binary16" through the station's config: parsed, and
// the Fastrak session and the pose conversion set up for the 16-bit packed records
// (the session selects them with `f`); a bad value names the three it accepts
// (label devices). The end-to-end run is tests/e2e/binary16_test.py.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "config/station_config.hpp"
#include "config_test_support.hpp"
#include "station_setup.hpp"

namespace twister::station_app {
namespace {

using ::testing::HasSubstr;

std::string config_with(const std::string& format_line) {
  return "[station]\njournal = \"/tmp/j.bin\"\nmesh = \"m.obj\"\n[tracker]\nbackend = \"sim\"\n" +
         format_line + "\n[buttons]\nbackend = \"sim\"\n";
}

TEST(TrackerFormatConfig, Binary16IsAcceptedAndReachesTheFastrakSession) {
  const auto r = parse_station_config(config_with("format = \"binary16\""), "t.toml");
  ASSERT_TRUE(r.ok()) << test::messages(r);
  EXPECT_EQ(r.config.tracker.format, RecordFormat::binary16);
  const auto setup = make_station_setup(r.config);
  ASSERT_TRUE(setup) << setup.error().message;
  EXPECT_EQ(setup->session.protocol.format, tracker::Format::binary16);
  EXPECT_EQ(setup->conversion.format, tracker::Format::binary16);
}

TEST(TrackerFormatConfig, TheOtherFormatsStayAsTheyWere) {
  for (const auto& [line, want] : {std::pair{"", tracker::Format::binary},
                                   std::pair{"format = \"binary\"", tracker::Format::binary},
                                   std::pair{"format = \"ascii\"", tracker::Format::ascii}}) {
    const auto r = parse_station_config(config_with(line), "t.toml");
    ASSERT_TRUE(r.ok()) << test::messages(r);
    const auto setup = make_station_setup(r.config);
    ASSERT_TRUE(setup) << setup.error().message;
    EXPECT_EQ(setup->session.protocol.format, want) << line;
  }
}

TEST(TrackerFormatConfig, ABadFormatNamesTheOnesAccepted) {
  const auto r = parse_station_config(config_with("format = \"bin16\""), "t.toml");
  EXPECT_FALSE(r.ok());
  EXPECT_THAT(test::messages(r),
              HasSubstr("t.toml:6: tracker.format: expected one of \"binary\" \"ascii\" "
                        "\"binary16\", got \"bin16\"\n"));
  EXPECT_FALSE(parse_station_config(config_with("format = 16"), "t.toml").ok());
}

}  // namespace
}  // namespace twister::station_app
