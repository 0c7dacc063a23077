// The device model playing a Liberty or Patriot (`--model`): the same scenario through
// the Fastrak model and each Liberty-family model, configured with the station's output
// lists and streamed in binary, gives the same poses when the Fastrak bytes go through
// FastrakParser and the Liberty bytes through LibertyParser; ASCII output is unchanged.
#include <gtest/gtest.h>

#include <cctype>
#include <string>
#include <vector>

#include "twister/sim/fastrak_device.hpp"
#include "twister/tracker/fastrak_parser.hpp"
#include "twister/tracker/liberty_parser.hpp"

namespace twister::sim {
namespace {

using tracker::FastrakPose;

// Two hands; the stylus (receiver 1) pressed from 1 s to 2 s.
constexpr const char* kScenario =
    "receivers 2\n"
    "duration 4\n"
    "key 0 1 10 -5 2 0 0 0 0\n"
    "key 1 1 12 -4 2 30 10 -20 1\n"
    "key 2 1 14 -3 1 60 -20 40 0\n"
    "key 4 1 10 -5 2 -90 45 170 0\n"
    "key 0 2 10 5 2 0 0 0\n"
    "key 4 2 16 2 -3 120 -30 60\n";

struct ModelRun {
  std::vector<std::byte> bytes;
  tracker::FastrakConfig protocol;
  FastrakDeviceCounters counters;
};

// Boots the model polled, sends the station's configuration one command at a time (a
// command arriving while another is processed is lost), then `C`, and collects 4 s.
ModelRun run(DeviceModel model, bool binary) {
  Scenario sc;
  std::string err;
  EXPECT_TRUE(parse_scenario(kScenario, sc, err)) << err;
  FastrakDeviceConfig cfg;
  cfg.model = model;
  FastrakDevice dev(cfg, sc, 0);
  // A Liberty-family unit takes its own item codes (position 2, quaternion 7, stylus 10,
  // CR LF 1; docs/liberty-protocol.md §3); the same lists as the Fastrak's 2, 11, 16, 1.
  const bool codes = model != DeviceModel::fastrak;
  // Each in its dialect (docs/liberty-protocol.md §9); the Fastrak's stylus told not to
  // toggle the stream (`e1,0`, as the station does), the Liberty's leaves it alone (an
  // empty line in its place keeps the commands' times the same).
  const std::vector<std::string> commands =
      codes ? std::vector<std::string>{"O1,2,7,10,1\r", "O2,2,7,1\r", "\r",
                                       binary ? "F1\r" : "F0\r", "C\r"}
            : std::vector<std::string>{"O1,2,11,16,1\r", "O2,2,11,1\r", "e1,0\r",
                                       binary ? "f" : "F", "C"};
  ModelRun r;
  std::int64_t t = 0;
  for (std::size_t i = 0; i <= commands.size(); ++i) {
    const std::int64_t until = 600'000 + static_cast<std::int64_t>(i) * 200'000;
    for (; t < until; t += 1'000) dev.advance(t, r.bytes);
    if (i < commands.size()) {
      dev.receive(reinterpret_cast<const std::byte*>(commands[i].data()), commands[i].size(), t);
    }
  }
  r.bytes.clear();  // replies to the commands
  for (; t < 5'000'000; t += 1'000) dev.advance(t, r.bytes);
  r.protocol = dev.protocol();
  r.counters = dev.counters();
  return r;
}

std::vector<FastrakPose> poses_of(const std::vector<tracker::FastrakEvent>& events) {
  std::vector<FastrakPose> out;
  for (const auto& e : events) {
    if (e.kind == tracker::EventKind::pose) out.push_back(e.pose);
  }
  return out;
}

std::vector<FastrakPose> parse_fastrak(const ModelRun& r) {
  tracker::FastrakParser p(r.protocol);
  std::vector<tracker::FastrakEvent> ev;
  p.feed(r.bytes, [&](const tracker::FastrakEvent& e) { ev.push_back(e); });
  return poses_of(ev);
}

std::vector<FastrakPose> parse_liberty(const ModelRun& r, tracker::LibertyModel model,
                                       tracker::LibertyParserCounters& counters) {
  tracker::LibertyConfig c;
  EXPECT_TRUE(tracker::to_liberty_config(r.protocol, model, c).ok());
  tracker::LibertyParser p(c);
  std::vector<tracker::FastrakEvent> ev;
  p.feed(r.bytes, [&](const tracker::FastrakEvent& e) { ev.push_back(e); });
  counters = p.counters();
  return poses_of(ev);
}

void expect_same_poses(const std::vector<FastrakPose>& a, const std::vector<FastrakPose>& b) {
  // The first record may be cut by the start of collection; longer frames finish later,
  // so the last one may still be on the wire. Align on the first common record.
  ASSERT_GT(a.size(), 400u);
  ASSERT_GT(b.size(), 400u);
  std::size_t ia = 0, ib = 0;
  while (ib < b.size() && !(b[ib].position == a[0].position)) ++ib;
  if (ib == b.size()) {
    ib = 0;
    while (ia < a.size() && !(a[ia].position == b[0].position)) ++ia;
  }
  ASSERT_LT(ia, 2u);
  ASSERT_LT(ib, 2u);
  const std::size_t n = std::min(a.size() - ia, b.size() - ib);
  ASSERT_GE(n + 2, std::max(a.size(), b.size()));
  std::size_t pressed = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const FastrakPose& x = a[ia + i];
    const FastrakPose& y = b[ib + i];
    ASSERT_EQ(x.station, y.station) << i;
    for (std::size_t k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(x.position[k], y.position[k]) << i;
    for (std::size_t k = 0; k < 4; ++k) EXPECT_FLOAT_EQ(x.quaternion[k], y.quaternion[k]) << i;
    EXPECT_EQ(x.has_button, y.has_button) << i;
    EXPECT_EQ(x.button, y.button) << i;
    EXPECT_EQ(x.status, y.status) << i;
    pressed += y.button;
  }
  EXPECT_GT(pressed, 20u);  // the stylus came through
}

TEST(LibertyDevice, LibertyFramesCarryTheFastrakPoses) {
  const ModelRun fastrak = run(DeviceModel::fastrak, true);
  const ModelRun liberty = run(DeviceModel::liberty, true);
  tracker::LibertyParserCounters k;
  const auto poses = parse_liberty(liberty, tracker::LibertyModel::liberty, k);
  expect_same_poses(parse_fastrak(fastrak), poses);
  EXPECT_EQ(k.bad_frames, 0u);
  EXPECT_LE(k.dropped_bytes, 50u);  // at most one frame cut by the start of collection
  EXPECT_EQ(liberty.counters.dropped_solutions, 0u);
  // The Fastrak parser finds nothing in Liberty frames.
  EXPECT_TRUE(parse_fastrak(liberty).empty());
}

TEST(LibertyDevice, PatriotFramesCarryTheFastrakPoses) {
  const ModelRun fastrak = run(DeviceModel::fastrak, true);
  const ModelRun patriot = run(DeviceModel::patriot, true);
  tracker::LibertyParserCounters k;
  expect_same_poses(parse_fastrak(fastrak),
                    parse_liberty(patriot, tracker::LibertyModel::patriot, k));
  EXPECT_EQ(k.bad_frames, 0u);
  // A Liberty parser hunts for "LY" and finds none of the Patriot's frames.
  tracker::LibertyParserCounters other;
  EXPECT_TRUE(parse_liberty(patriot, tracker::LibertyModel::liberty, other).empty());
}

TEST(LibertyDevice, AsciiOutputIsTheFastraksForEveryModel) {
  const ModelRun fastrak = run(DeviceModel::fastrak, false);
  const ModelRun liberty = run(DeviceModel::liberty, false);
  EXPECT_EQ(fastrak.bytes, liberty.bytes);
  EXPECT_GT(fastrak.bytes.size(), 10'000u);
}

// The Liberty dialect in lower case, as polhemus_ros_driver sends it (`f1`, `c`, `h*`,
// `p`; docs/liberty-protocol.md §9), is heard as the upper case: each line a command,
// `p` a poll, none an error (liberty_command_fuzz found lower case refused with -99).
TEST(LibertyDevice, CommandLinesInLowerCaseAreTheUpperCase) {
  CommandTimes times = instant_commands();
  for (const char* line : {"f1\r", "c\r", "u1\r", "h1,0,0,1\r", "x0,1,0,0\r", "o1,2,7,1\r"}) {
    CommandInput lower(times, kInputBufferBytes, true);
    CommandInput upper(times, kInputBufferBytes, true);
    CommandInput::Heard heard_lower = CommandInput::Heard::nothing;
    CommandInput::Heard heard_upper = CommandInput::Heard::nothing;
    for (const char* c = line; *c != '\0'; ++c) {
      heard_lower = lower.take(*c, 0);
      heard_upper = upper.take(static_cast<char>(std::toupper(static_cast<unsigned char>(*c))), 0);
    }
    ASSERT_EQ(heard_lower, CommandInput::Heard::command) << line;
    ASSERT_EQ(heard_upper, CommandInput::Heard::command) << line;
    EXPECT_EQ(tracker::letter(lower.command()), tracker::letter(upper.command())) << line;
  }
  CommandInput poll(times, kInputBufferBytes, true);
  ASSERT_EQ(poll.take('p', 0), CommandInput::Heard::command);
  EXPECT_EQ(tracker::letter(poll.command()), 'P');
}

}  // namespace
}  // namespace twister::sim
