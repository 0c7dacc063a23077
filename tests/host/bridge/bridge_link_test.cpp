// Station -> bridge over the link, in process: StationLink driven by a real
// SculptSession, BridgeApp (no display) on the other end of an in-memory wire.
// Covers first sync, live frames, commits verified by checksum, link loss with a
// commit made meanwhile (resync by version), reconnect without changes (no full
// resend) and line noise inside a commit (mismatch -> resend -> identical mesh).
#include <gtest/gtest.h>

#include "bridge_link_rig.hpp"

namespace twister::bridge {
namespace {

// The rig of every test here: a station and a bridge that logs nowhere.
struct Rig : test_support::BridgeLinkRig {
  Rig() : BridgeLinkRig(null_log) {}
  static inline ports::NullLogSink null_log;
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
