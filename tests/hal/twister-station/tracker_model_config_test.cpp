// Issue 22: [tracker] model = "fastrak" | "liberty" | "patriot" through the station's
// config: parsed (fastrak by default), reaching the tracker session and the simulated
// unit; a bad value names the three accepted, and a Liberty-family model with a
// format other than binary is refused (label devices). The PTY end-to-end runs are
// tests/e2e/pty_chain_test.py --model.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "config/station_config.hpp"
#include "config_test_support.hpp"
#include "station_setup.hpp"

namespace twister::station_app {
namespace {

using ::testing::HasSubstr;

std::string config_with(const std::string& lines) {
  return "[station]\njournal = \"/tmp/j.bin\"\nmesh = \"m.obj\"\n[tracker]\nbackend = \"sim\"\n" +
         lines + "\n[buttons]\nbackend = \"sim\"\n";
}

TEST(TrackerModelConfig, EachModelReachesTheTrackerSession) {
  for (const auto& [line, want, session] :
       {std::tuple{"", TrackerModel::fastrak, tracker::TrackerModel::fastrak},
        std::tuple{"model = \"fastrak\"", TrackerModel::fastrak, tracker::TrackerModel::fastrak},
        std::tuple{"model = \"liberty\"", TrackerModel::liberty, tracker::TrackerModel::liberty},
        std::tuple{"model = \"patriot\"\nformat = \"binary\"", TrackerModel::patriot,
                   tracker::TrackerModel::patriot}}) {
    const auto r = parse_station_config(config_with(line), "t.toml");
    ASSERT_TRUE(r.ok()) << line << "\n" << test::messages(r);
    EXPECT_EQ(r.config.tracker.model, want) << line;
    const auto setup = make_station_setup(r.config);
    ASSERT_TRUE(setup) << setup.error().message;
    EXPECT_EQ(setup->session.model, session) << line;
    EXPECT_EQ(setup->session.protocol.format, tracker::Format::binary);
  }
}

TEST(TrackerModelConfig, ABadModelNamesTheOnesAccepted) {
  const auto r = parse_station_config(config_with("model = \"viper\""), "t.toml");
  EXPECT_FALSE(r.ok());
  EXPECT_THAT(test::messages(r),
              HasSubstr("t.toml:6: tracker.model: expected one of \"fastrak\" \"liberty\" "
                        "\"patriot\" \"latus\", got \"viper\"\n"));
  EXPECT_FALSE(parse_station_config(config_with("model = 2"), "t.toml").ok());
}

TEST(TrackerModelConfig, LibertyAndPatriotNeedBinary) {
  for (const char* model : {"liberty", "patriot"}) {
    for (const char* format : {"ascii", "binary16"}) {
      const auto r = parse_station_config(
          config_with(std::string("model = \"") + model + "\"\nformat = \"" + format + "\""),
          "t.toml");
      EXPECT_FALSE(r.ok());
      EXPECT_THAT(
          test::messages(r),
          HasSubstr(std::string("tracker.format: expected \"binary\" with tracker.model "
                                "= \"") +
                    model + "\" (its frames are read in binary only), got \"" + format + "\""));
    }
  }
  // The Fastrak keeps every format.
  EXPECT_TRUE(
      parse_station_config(config_with("model = \"fastrak\"\nformat = \"ascii\""), "t.toml").ok());
}

}  // namespace
}  // namespace twister::station_app
