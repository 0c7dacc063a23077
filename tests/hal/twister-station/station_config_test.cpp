// Malformed configs give the messages documented in docs/hardware.md ("Config errors").
#include "config/station_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "config_test_support.hpp"

namespace twister::station_app {
namespace {

using test::messages;

using ::testing::HasSubstr;

constexpr const char* kValidSerial = R"(
[station]
journal = "/tmp/j.bin"
mesh = "m.obj"
[tracker]
backend = "serial"
[tracker.serial]
device = "/dev/twister-fastrak"
[buttons]
backend = "gpiod"
[buttons.gpiod]
lines = [17, 27]
)";

ConfigParseResult parse(const std::string& text) { return parse_station_config(text, "t.toml"); }

TEST(StationConfigTest, DeployExamplesAreValid) {
  for (const char* name : {"/station.toml", "/sim.toml"}) {
    const auto r = load_station_config(std::string(TWISTER_DEPLOY_DIR) + name);
    EXPECT_TRUE(r.ok()) << name << "\n" << messages(r);
  }
  const auto r = load_station_config(std::string(TWISTER_DEPLOY_DIR) + "/station.toml");
  EXPECT_EQ(r.config.tracker.backend, TrackerBackend::serial);
  EXPECT_EQ(r.config.tracker.serial.baud, 115200u);
  EXPECT_EQ(r.config.tracker.usb.vendor_id, 0x0f44);
  EXPECT_EQ(r.config.tracker.usb.endpoint_in, 0);  // from the descriptor
  ASSERT_EQ(r.config.buttons.gpiod.lines.size(), 2u);
  EXPECT_EQ(r.config.buttons.gpiod.lines[1], 27u);
  EXPECT_EQ(r.config.buttons.gpiod.bias, GpioBias::pull_up);
  ASSERT_EQ(r.config.buttons.hidapi.buttons.size(), 2u);
  EXPECT_EQ(r.config.buttons.hidapi.buttons[1].mask, 0x08);
}

TEST(StationConfigTest, MinimalSerialConfigTakesDefaults) {
  const auto r = parse(kValidSerial);
  ASSERT_TRUE(r.ok()) << messages(r);
  EXPECT_EQ(r.config.station.loop_timeout_ms, 10u);
  EXPECT_EQ(r.config.tracker.left_station, 1);
  EXPECT_EQ(r.config.tracker.right_station, 2);
  EXPECT_EQ(r.config.tracker.serial.flow_control, SerialFlowControl::none);
  EXPECT_TRUE(r.config.buttons.gpiod.active_low);
}

TEST(StationConfigTest, SyntaxErrorNamesFileAndLine) {
  const auto r = parse("[station]\njournal = \"x\"\nbad line here\n");
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].line, 3u);
  EXPECT_EQ(r.errors[0].to_string().rfind("t.toml:3: TOML syntax error: ", 0), 0u) << messages(r);
}

TEST(StationConfigTest, UnknownKeyIsAnErrorWithAllowedKeys) {
  std::string text = kValidSerial;
  text += "[systemd]\nnotfy = true\n";
  const auto r = parse(text);
  ASSERT_EQ(r.errors.size(), 1u) << messages(r);
  EXPECT_EQ(r.errors[0].to_string(),
            "t.toml:14: systemd.notfy: unknown key (allowed here: notify, watchdog)");
}

TEST(StationConfigTest, WrongTypeNamesExpectedForm) {
  const auto r = parse(R"([station]
journal = "/tmp/j"
mesh = "m.obj"
loop_timeout_ms = "fast"
[tracker]
backend = "sim"
[buttons]
backend = "stylus"
)");
  ASSERT_EQ(r.errors.size(), 1u) << messages(r);
  EXPECT_EQ(r.errors[0].to_string(),
            "t.toml:4: station.loop_timeout_ms: expected an integer from 1 to 1000, got \"fast\"");
}

TEST(StationConfigTest, OutOfRangeAndBadEnumValues) {
  const auto r = parse(R"([station]
journal = "/tmp/j"
mesh = "m.obj"
[tracker]
backend = "serial"
left_station = 7
[tracker.serial]
device = "/dev/ttyS0"
baud = 12345
flow_control = "hardware"
[buttons]
backend = "gpio"
)");
  const std::string m = messages(r);
  EXPECT_THAT(
      m, HasSubstr("t.toml:6: tracker.left_station: expected an integer from 1 to 4, got 7\n"));
  EXPECT_THAT(m,
              HasSubstr("t.toml:9: tracker.serial.baud: expected one of 2400 4800 9600 19200 38400 "
                        "57600 115200, got 12345\n"));
  EXPECT_THAT(
      m, HasSubstr("t.toml:10: tracker.serial.flow_control: expected one of \"none\" \"rtscts\" "
                   "\"xonxoff\", got \"hardware\"\n"));
  EXPECT_THAT(
      m, HasSubstr("t.toml:12: buttons.backend: expected one of \"gpiod\" \"hidapi\" \"stylus\" "
                   "\"sim\", got \"gpio\"\n"));
  EXPECT_EQ(r.errors.size(), 4u) << m;
}

TEST(StationConfigTest, MissingRequiredKeysAndSections) {
  const auto r = parse("[station]\n[tracker]\nbackend = \"serial\"\n");
  const std::string m = messages(r);
  EXPECT_THAT(m, HasSubstr("t.toml:1: station.journal: missing required key; expected a string\n"));
  EXPECT_THAT(m, HasSubstr("t.toml:1: station.mesh: missing required key; expected a string\n"));
  EXPECT_THAT(m, HasSubstr("t.toml:2: tracker.serial: missing required key; expected a table "
                           "[tracker.serial]\n"));
  EXPECT_THAT(m,
              HasSubstr("t.toml:1: buttons: missing required key; expected a table [buttons]\n"));
}

TEST(StationConfigTest, SameReceiverForBothHandsIsRefused) {
  std::string text = kValidSerial;
  text.replace(text.find("backend = \"serial\""), 18, "backend = \"serial\"\nright_station = 1");
  const auto r = parse(text);
  ASSERT_EQ(r.errors.size(), 1u) << messages(r);
  EXPECT_EQ(r.errors[0].to_string(),
            "t.toml:7: tracker.right_station: expected a receiver "
            "different from tracker.left_station (both are 1)");
}

TEST(StationConfigTest, SimButtonsAreAcceptedWithTheSimTrackerOnly) {
  const auto ok = parse(R"([station]
journal = "/tmp/j"
mesh = "m.obj"
[tracker]
backend = "sim"
[buttons]
backend = "sim"
)");
  EXPECT_TRUE(ok.errors.empty()) << messages(ok);
  EXPECT_EQ(ok.config.buttons.backend, ButtonBackend::sim);
  EXPECT_STREQ(to_string(ButtonBackend::sim), "sim");
  const auto bad = parse(R"([station]
journal = "/tmp/j"
mesh = "m.obj"
[tracker]
backend = "serial"
[tracker.serial]
device = "/dev/ttyUSB0"
[buttons]
backend = "sim"
)");
  const std::string m = messages(bad);
  EXPECT_THAT(m,
              HasSubstr("t.toml:9: buttons.backend: \"sim\" plays the simulator scenario's button "
                        "lines and needs tracker.backend = \"sim\"\n"));
  EXPECT_EQ(bad.errors.size(), 1u) << m;
}

TEST(StationConfigTest, GpiodLineListIsChecked) {
  const auto r = parse(R"([station]
journal = "/tmp/j"
mesh = "m.obj"
[tracker]
backend = "sim"
[buttons]
backend = "gpiod"
[buttons.gpiod]
lines = [3, -1, 3]
bias = "up"
)");
  const std::string m = messages(r);
  EXPECT_THAT(
      m,
      HasSubstr("t.toml:9: buttons.gpiod.lines: expected line offsets from 0 to 1023, got -1\n"));
  EXPECT_THAT(
      m, HasSubstr("t.toml:9: buttons.gpiod.lines: expected each line offset once, got 3 twice\n"));
  EXPECT_THAT(m, HasSubstr("t.toml:10: buttons.gpiod.bias: expected one of \"as-is\" \"disable\" "
                           "\"pull-up\" \"pull-down\", got \"up\"\n"));
  EXPECT_EQ(r.errors.size(), 3u) << m;
}

TEST(StationConfigTest, HidapiButtonEntriesAreChecked) {
  const auto r = parse(R"([station]
journal = "/tmp/j"
mesh = "m.obj"
[tracker]
backend = "sim"
[buttons]
backend = "hidapi"
[buttons.hidapi]
vendor_id = 0x05f3
buttons = [ { byte = 1, mask = 0 }, 5, { byte = 2, mask = 1, bit = 3 } ]
)");
  const std::string m = messages(r);
  EXPECT_THAT(m, HasSubstr("t.toml:8: buttons.hidapi.product_id: missing required key; expected an "
                           "integer from 0 to 65535\n"));
  EXPECT_THAT(
      m, HasSubstr("t.toml:10: buttons.hidapi.buttons[0].mask: expected an integer from 1 to 255, "
                   "got 0\n"));
  EXPECT_THAT(
      m, HasSubstr("t.toml:10: buttons.hidapi.buttons[1]: expected an inline table { byte = N, "
                   "mask = M }, got an integer\n"));
  EXPECT_THAT(
      m, HasSubstr("t.toml:10: buttons.hidapi.buttons[2].bit: unknown key (allowed here: byte, "
                   "mask)\n"));
  EXPECT_EQ(r.errors.size(), 4u) << m;
}

TEST(StationConfigTest, NonAsciiIsRefusedBeforeToml) {
  // Minimised from a station_config_fuzz crash: UB inside toml++ 3.3.0 on such input.
  const auto r = parse("# ok\n# caf\xc3\xa9\n[station]\n");
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].to_string(),
            "t.toml:2: non-ASCII byte 0xC3; the config must be plain ASCII (also in comments)");
}

TEST(StationConfigTest, UnreadableFileIsOneErrorAtLineZero) {
  const auto r = load_station_config("/nonexistent/station.toml");
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].to_string(),
            "/nonexistent/station.toml:0: cannot read the config file (missing or no permission)");
}

}  // namespace
}  // namespace twister::station_app
