// twister-sim's server playing a Liberty / Patriot on a real PTY (`--model`): a raw host
// configures the station's output lists (in the Liberty's item codes), binary and
// continuous, and the frames it reads parse with LibertyParser to the poses the Fastrak model gives
// for the same still hands through FastrakParser in process (equal as floats). Real time, about 2 s
// per model.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <vector>

#include "sim_pty_rig.hpp"
#include "twister/tracker/fastrak_parser.hpp"
#include "twister/tracker/liberty_parser.hpp"

namespace twister::sim {
namespace {

using test_rig::RawClient;
using test_rig::SimThread;
using tracker::EventKind;
using tracker::Format;
using tracker::Item;
using tracker::OutputList;

// Still hands, so a pose does not depend on when it was sampled.
constexpr const char* kStill =
    "receivers 2\n"
    "key 0 1 11.5 -4.25 2.75 30 -20 45 1\n"
    "key 0 2 9.5 6.125 -1.5 -120 60 -10\n";

tracker::FastrakConfig station_lists() {
  tracker::FastrakConfig c;
  c.format = Format::binary;
  c.stations[0] = {true,
                   OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf})};
  c.stations[1] = {true, OutputList::of({Item::position, Item::quaternion, Item::crlf})};
  return c;
}

// The Fastrak model's pose per station, in process (virtual time).
std::map<int, tracker::FastrakPose> fastrak_poses() {
  FastrakDeviceConfig cfg;
  cfg.reset_time_us = 0;
  FastrakDevice dev(cfg, test_rig::scenario(kStill), 0);
  std::vector<std::byte> out;
  std::int64_t t = 0;
  for (const char* cmd : {"O1,2,11,16,1\r", "O2,2,11,1\r", "f", "C"}) {
    for (const std::int64_t until = t + 200'000; t < until; t += 1'000) dev.advance(t, out);
    dev.receive(reinterpret_cast<const std::byte*>(cmd), std::strlen(cmd), t);
  }
  out.clear();
  for (const std::int64_t until = t + 500'000; t < until; t += 1'000) dev.advance(t, out);
  tracker::FastrakParser parser(station_lists());
  std::map<int, tracker::FastrakPose> poses;
  parser.feed(out, [&](const tracker::FastrakEvent& e) {
    if (e.kind == EventKind::pose) poses[e.pose.station] = e.pose;
  });
  return poses;
}

void check_model(DeviceModel model, tracker::LibertyModel family, const char* name) {
  SCOPED_TRACE(name);
  const auto want = fastrak_poses();
  ASSERT_EQ(want.size(), 2u);
  FastrakDeviceConfig dev;
  dev.model = model;
  dev.reset_time_us = 0;
  FastrakDevice device(dev, test_rig::scenario(kStill), 0);
  ServeOptions opts;
  opts.link = test_rig::link_path(name);
  DeviceServer server(device, opts);
  ASSERT_TRUE(server.start());
  SimThread sim(server);
  RawClient host(opts.link, B115200);
  ASSERT_TRUE(host.ok());
  // One command at a time: the unit is deaf while it processes one.
  // The family's own item codes: position 2, quaternion 7, stylus 10, CR LF 1.
  // The Liberty's dialect (docs/liberty-protocol.md §9): WhoAmI answered with a line
  // starting '0', then binary (`F1`) and continuous (`C`), each a line.
  host.send("\x16\r");
  EXPECT_EQ(
      host.read_until([](const std::string& s) { return s.find('\n') != std::string::npos; }, 2000)
          .substr(0, 1),
      "0");
  for (const char* cmd : {"O1,2,7,10,1\r", "O2,2,7,1\r", "F1\r"}) {
    host.send(cmd);
    host.read_for(200);
  }
  host.send("C\r");
  const std::string bytes =
      host.read_until([](const std::string& s) { return s.size() >= 42u * 200u; }, 6000);
  sim.join();

  tracker::LibertyConfig config;
  ASSERT_TRUE(tracker::to_liberty_config(station_lists(), family, config).ok());
  tracker::LibertyParser parser(config);
  std::map<int, std::size_t> count;
  parser.feed(std::as_bytes(std::span<const char>(bytes.data(), bytes.size())),
              [&](const tracker::FastrakEvent& e) {
                if (e.kind != EventKind::pose) return;
                const tracker::FastrakPose& w = want.at(e.pose.station);
                ++count[e.pose.station];
                for (std::size_t k = 0; k < 3; ++k) {
                  EXPECT_FLOAT_EQ(e.pose.position[k], w.position[k]);
                }
                for (std::size_t k = 0; k < 4; ++k) {
                  EXPECT_FLOAT_EQ(e.pose.quaternion[k], w.quaternion[k]);
                }
                EXPECT_EQ(e.pose.button, w.button);
              });
  EXPECT_GE(count[1], 90u);
  EXPECT_GE(count[2], 90u);
  EXPECT_EQ(parser.counters().bad_frames, 0u);
  EXPECT_LE(parser.counters().dropped_bytes, 42u);  // a frame cut by the start of reading
  EXPECT_TRUE(want.at(1).button);
}

TEST(LibertyPty, LibertyFramesOnAPtyCarryTheFastrakPoses) {
  check_model(DeviceModel::liberty, tracker::LibertyModel::liberty, "liberty");
}

TEST(LibertyPty, PatriotFramesOnAPtyCarryTheFastrakPoses) {
  check_model(DeviceModel::patriot, tracker::LibertyModel::patriot, "patriot");
}

}  // namespace
}  // namespace twister::sim
