// Station -> bridge over the link, in process: StationLink driven by a real
// SculptSession, BridgeApp (no display) on the other end of an in-memory wire.
// Covers first sync, live frames, commits verified by checksum, link loss with a
// commit made meanwhile (resync by version), reconnect without changes (no full
// resend) and line noise inside a commit (mismatch -> resend -> identical mesh).
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "bridge_app.hpp"
#include "fakes/memory_wire.hpp"
#include "session_harness.hpp"
#include "twister/station/station_link.hpp"

namespace twister::bridge {
namespace {

using input::test_support::kGrab0;
using input::test_support::Station;
using input::test_support::z_turn;

struct Rig {
  Rig()
      : station_end(wire, true), bridge_end(wire, false), bridge(bridge_end, nullptr, {{}, false}) {
    const std::size_t n = station.mesh.vertex_capacity();
    x.resize(n);
    y.resize(n);
    z.resize(n);
    idx.resize(3 * station.mesh.triangle_capacity());
    out.resize(64 * link::kMaxFrameBytes);
    link = std::make_unique<station::StationLink>(
        station_end, station::StationLinkStorage{x, y, z, idx, out}, station::StationLinkConfig{});
    EXPECT_TRUE(link->start(*station.session).ok());
  }
  void run(int rounds = 20) {
    for (int i = 0; i < rounds; ++i) {
      bridge.step();
      link->poll(*station.session, station.now_us);
    }
    bridge.step();
  }
  void stroke(double lift) {
    station.hand(0, math::identity_frame({0, 0, 0}));
    station.button(kGrab0, true);
    (void)station.tick();
    run(2);
    for (int k = 1; k <= 4; ++k) {
      station.hand(0, z_turn({0.1 * k, 0, lift * k}, 0.2 * k));
      (void)station.tick();
      run(2);
    }
    station.button(kGrab0, false);
    (void)station.tick();
  }

  Station station;
  test::MemoryWire wire;
  test::MemoryLinkEnd station_end;
  test::MemoryLinkEnd bridge_end;
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> idx;
  std::vector<std::byte> out;
  std::unique_ptr<station::StationLink> link;
  BridgeApp bridge;
};

TEST(BridgeLink, SyncLiveCommitAndResyncAfterLinkLoss) {
  Rig r;
  r.run();
  const SceneReplica& rep = r.bridge.replica();
  ASSERT_EQ(rep.version(), 1u);
  EXPECT_EQ(rep.checksum(), r.station.mesh.checksum());
  EXPECT_EQ(rep.counters().full_meshes, 1u);

  r.stroke(0.1);
  EXPECT_GT(rep.counters().live_frames, 3u);
  r.run();
  EXPECT_EQ(rep.version(), 2u);
  EXPECT_EQ(rep.counters().commits, 1u);
  EXPECT_EQ(rep.checksum(), r.station.mesh.checksum());

  // Link loss; the station goes on and commits a stroke meanwhile.
  r.wire.cut();
  r.run(3);
  EXPECT_FALSE(r.bridge.connected());
  r.stroke(-0.1);
  r.run(3);
  EXPECT_NE(rep.checksum(), r.station.mesh.checksum());
  r.wire.up = true;
  r.run();
  EXPECT_TRUE(r.bridge.connected());
  EXPECT_EQ(rep.version(), 3u);
  EXPECT_EQ(rep.checksum(), r.station.mesh.checksum());
  EXPECT_EQ(rep.counters().full_meshes, 2u);

  // Reconnect with nothing changed: resync by version, no full resend.
  r.wire.cut();
  r.run(3);
  r.wire.up = true;
  r.run();
  EXPECT_EQ(r.bridge.counters().connects, 3u);
  EXPECT_EQ(rep.counters().full_meshes, 2u);
  EXPECT_EQ(rep.checksum(), r.station.mesh.checksum());
}

TEST(BridgeLink, NoiseInsideACommitEndsInAResendAndTheSameMesh) {
  Rig r;
  r.run();
  r.stroke(0.15);
  // The commit set is queued by this poll; garble a byte in the middle of it.
  r.link->poll(*r.station.session, r.station.now_us);
  ASSERT_GT(r.wire.a_to_b.size(), 200u);
  r.wire.a_to_b.flip(r.wire.a_to_b.size() / 2, std::byte{0x5a});
  r.run(40);
  const SceneReplica& rep = r.bridge.replica();
  EXPECT_GE(r.bridge.decoder_counters().bad_crc + r.bridge.decoder_counters().bad_cobs, 1u);
  EXPECT_GE(rep.counters().resend_requests, 1u);
  EXPECT_EQ(rep.checksum(), r.station.mesh.checksum());
  EXPECT_EQ(rep.version(), r.link->mesh_version());
}

}  // namespace
}  // namespace twister::bridge
