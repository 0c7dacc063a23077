// station.toml [link] (issues 11 and 14): every key's good and bad forms, each
// error naming file, line, key and the expected form; the rules across keys.
#include "config/link_config.hpp"

#include <gtest/gtest.h>

#include <string>

#include "config/station_config.hpp"
#include "config_test_support.hpp"

namespace twister::station_app {
namespace {

using test::messages;

const std::string kBase = R"([station]
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

ConfigParseResult parse_link(const std::string& link) {
  return parse_station_config(kBase + "[link]\n" + link, "t.toml");
}

TEST(LinkConfig, DefaultsAndAGoodSection) {
  const auto none = parse_station_config(kBase, "t.toml");
  ASSERT_TRUE(none.ok()) << messages(none);
  EXPECT_TRUE(none.config.link.address.empty());
  EXPECT_EQ(none.config.link.socket_mode, 0660u);
  EXPECT_EQ(none.config.link.listen, LinkListen::loopback);
  EXPECT_EQ(none.config.link.baud, 230400u);
  const auto r = parse_link(
      "address = \"tcp:10.0.0.5:7000\"\nsocket_mode = 0o600\nsocket_group = \"twister\"\n"
      "listen = \"network\"\npsk_file = \"/etc/twister/link.key\"\nbaud = 921600\n");
  ASSERT_TRUE(r.ok()) << messages(r);
  EXPECT_EQ(r.config.link.address, "tcp:10.0.0.5:7000");
  EXPECT_EQ(r.config.link.socket_mode, 0600u);
  EXPECT_EQ(r.config.link.socket_group, "twister");
  EXPECT_EQ(r.config.link.listen, LinkListen::network);
  EXPECT_EQ(r.config.link.psk_file, "/etc/twister/link.key");
  EXPECT_EQ(r.config.link.baud, 921600u);
  for (const char* a : {"unix:/run/twister/link.sock", "serial:/dev/twister-display"}) {
    const auto ok = parse_link(std::string("address = \"") + a + "\"\n");
    EXPECT_TRUE(ok.ok()) << a << "\n" << messages(ok);
  }
}

// Issue 21 item 5: without a key, any local user could take a loopback TCP display
// link; it is refused unless allowed explicitly (a Unix socket with a group is the
// keyless default).
TEST(LinkConfig, KeylessLoopbackTcpIsRefusedUnlessAllowed) {
  const auto keyless = parse_link("address = \"tcp:127.0.0.1:7000\"\n");
  ASSERT_FALSE(keyless.ok());
  EXPECT_NE(messages(keyless).find("link.address: expected psk_file with a tcp: address"),
            std::string::npos)
      << messages(keyless);
  EXPECT_NE(messages(keyless).find("allow_unauthenticated_tcp = true"), std::string::npos);
  const auto allowed =
      parse_link("address = \"tcp:127.0.0.1:7000\"\nallow_unauthenticated_tcp = true\n");
  EXPECT_TRUE(allowed.ok()) << messages(allowed);
  EXPECT_TRUE(allowed.config.link.allow_unauthenticated_tcp);
  const auto keyed =
      parse_link("address = \"tcp:127.0.0.1:7000\"\npsk_file = \"/etc/twister/link.key\"\n");
  EXPECT_TRUE(keyed.ok()) << messages(keyed);
  // --link overrides the address at start: the same rule is applied there.
  LinkSection over;
  over.address = "tcp:127.0.0.1:7000";
  EXPECT_FALSE(internal::unauthenticated_tcp_problem(over).empty());
  over.allow_unauthenticated_tcp = true;
  EXPECT_TRUE(internal::unauthenticated_tcp_problem(over).empty());
}

TEST(LinkConfig, BadValuesNameFileLineKeyAndExpectedForm) {
  struct Case {
    const char* text;
    const char* want;
  };
  const Case cases[] = {
      {"address = \"bogus\"\n", "t.toml:13: link.address: expected unix:PATH, tcp:A.B.C.D:PORT"},
      {"address = \"tcp:127.0.0.1\"\n", "link.address: expected tcp:A.B.C.D:PORT"},
      {"address = \"tcp:localhost:80\"\n", "link.address: expected tcp:A.B.C.D:PORT (IPv4"},
      {"address = \"tcp:127.0.0.1:70000\"\n", "port 1..65535"},
      {"address = 5\n", "link.address: expected a string, got an integer"},
      {"socket_mode = 0o1777\n", "link.socket_mode: expected an integer from 0 to 511"},
      {"socket_mode = 0o066\n", "owner read and write"},
      {"socket_group = \"\"\n", "link.socket_group: expected a non-empty string"},
      {"listen = \"everywhere\"\n", "link.listen: expected one of \"loopback\" \"network\""},
      {"psk_file = 1\n", "link.psk_file: expected a string"},
      {"baud = 115201\n", "link.baud: expected one of 9600 19200"},
      {"speed = 1\n", "link.speed: unknown key"},
  };
  for (const Case& c : cases) {
    const auto r = parse_link(c.text);
    EXPECT_FALSE(r.ok()) << c.text;
    EXPECT_NE(messages(r).find(c.want), std::string::npos) << c.text << "\n" << messages(r);
  }
}

TEST(LinkConfig, BeyondLoopbackNeedsNetworkListenAndNetworkNeedsAKey) {
  const auto open = parse_link("address = \"tcp:0.0.0.0:7000\"\n");
  ASSERT_FALSE(open.ok());
  EXPECT_NE(messages(open).find("link.address: expected a loopback address"), std::string::npos)
      << messages(open);
  const auto keyless = parse_link("address = \"tcp:0.0.0.0:7000\"\nlisten = \"network\"\n");
  ASSERT_FALSE(keyless.ok());
  EXPECT_NE(messages(keyless).find("t.toml:14: link.listen: expected psk_file"), std::string::npos)
      << messages(keyless);
}

}  // namespace
}  // namespace twister::station_app

namespace twister::station_app {
namespace {

// Issue 25 (spectators): [link] max_spectators 0..8 (default 4) and
// spectator_stall_seconds 0.1..600 (default 5); anything else names key and range.
TEST(LinkConfig, SpectatorSlotsAndStallTime) {
  const auto none = parse_station_config(kBase, "t.toml");
  ASSERT_TRUE(none.ok()) << messages(none);
  EXPECT_EQ(none.config.link.max_spectators, 4u);
  EXPECT_EQ(none.config.link.spectator_stall_seconds, 5.0);
  const auto r = parse_link("max_spectators = 0\nspectator_stall_seconds = 2.5\n");
  ASSERT_TRUE(r.ok()) << messages(r);
  EXPECT_EQ(r.config.link.max_spectators, 0u);
  EXPECT_EQ(r.config.link.spectator_stall_seconds, 2.5);
  const auto many = parse_link("max_spectators = 9\n");
  EXPECT_NE(messages(many).find("link.max_spectators: expected an integer from 0 to 8, got 9"),
            std::string::npos)
      << messages(many);
  const auto stall = parse_link("spectator_stall_seconds = 0\n");
  EXPECT_NE(messages(stall).find("link.spectator_stall_seconds: expected a number from 0.1 to 600"),
            std::string::npos)
      << messages(stall);
}

}  // namespace
}  // namespace twister::station_app
