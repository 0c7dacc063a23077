#include "twister/station/station_link.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "fakes/memory_wire.hpp"
#include "session_harness.hpp"
#include "support/allocation_counter.hpp"

namespace twister::link {
namespace {

using session::test_support::kGrab0;
using session::test_support::Station;
using station::StationLink;
using station::StationLinkConfig;
using station::StationLinkStorage;

struct Rig {
  Rig() : station_end(wire, true), bridge_end(wire, false) {
    const std::size_t n = station.mesh.vertex_capacity();
    x.resize(n);
    y.resize(n);
    z.resize(n);
    idx.resize(3 * station.mesh.triangle_capacity());
    out.resize(64 * kMaxFrameBytes);
    link = std::make_unique<StationLink>(station_end, StationLinkStorage{x, y, z, idx, out},
                                         StationLinkConfig{});
    EXPECT_TRUE(link->start(*station.session).ok());
  }
  // Bridge side: sends raw messages, decodes everything the station sent.
  template <LinkBody M>
  void bridge_send(const M& m) {
    std::vector<std::byte> f(kMaxFrameBytes);
    const auto n = encode_frame(m, f);
    ASSERT_TRUE(n.ok());
    f.resize(*n);
    ASSERT_EQ(*bridge_end.send(f), f.size());
  }
  std::vector<LinkMessage> bridge_receive() {
    std::vector<LinkMessage> got;
    std::vector<std::byte> buf(1 << 16);
    for (;;) {
      const auto n = bridge_end.receive(buf);
      if (!n.ok() || *n == 0) break;
      for (std::size_t i = 0; i < *n; ++i) {
        if (const auto m = decoder.process(buf[i]); m.ok()) got.push_back(**m);
      }
    }
    return got;
  }
  void poll() { link->poll(*station.session, station.now_us); }

  Station station;
  test::MemoryWire wire;
  test::MemoryLinkEnd station_end;
  test::MemoryLinkEnd bridge_end;
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> idx;
  std::vector<std::byte> out;
  std::unique_ptr<StationLink> link;
  LinkDecoder decoder;
};

std::size_t count(const std::vector<LinkMessage>& ms, MessageType t) {
  std::size_t n = 0;
  for (const auto& m : ms) n += type_of(m) == t ? 1 : 0;
  return n;
}

Hello bridge_hello(std::uint32_t version, std::uint64_t checksum) {
  return Hello{Role::bridge, 0, version, checksum, {}};
}

TEST(StationLink, FullMeshOnHelloThenCommitWithChecksumAndNoHeapInPoll) {
  Rig r;
  r.bridge_send(bridge_hello(0, 0));
  for (int i = 0; i < 50; ++i) r.poll();
  auto got = r.bridge_receive();
  ASSERT_GE(got.size(), 3u);
  EXPECT_EQ(type_of(got.front()), MessageType::hello);
  EXPECT_EQ(count(got, MessageType::mesh_end), 1u);
  EXPECT_EQ(type_of(got.back()) == MessageType::mesh_end || count(got, MessageType::status) > 0,
            true);
  for (const auto& m : got) {
    if (const auto* e = std::get_if<MeshEnd>(&m)) {
      EXPECT_EQ(e->version, 1u);
      EXPECT_EQ(e->checksum, r.station.mesh.checksum());
    }
  }
  // A stroke: live frames while dragging, then one commit set (begin..end).
  Station& s = r.station;
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  std::size_t live = 0;
  for (int k = 1; k <= 5; ++k) {
    s.hand(0, session::test_support::z_turn({0, 0, 0.05 * k}, 0.1 * k));
    (void)s.tick();
    EXPECT_NO_ALLOCATIONS(r.poll());
    live += count(r.bridge_receive(), MessageType::hands);
  }
  EXPECT_GE(live, 4u);
  s.button(kGrab0, false);
  (void)s.tick();
  EXPECT_NO_ALLOCATIONS(r.poll());
  got = r.bridge_receive();
  ASSERT_EQ(count(got, MessageType::mesh_end), 1u);
  bool begin_seen = false;
  for (const auto& m : got) {
    if (const auto* b = std::get_if<MeshBegin>(&m)) {
      begin_seen = true;
      EXPECT_FALSE(b->full);
      EXPECT_EQ(b->base_version, 1u);
      EXPECT_EQ(b->version, 2u);
    }
    if (const auto* e = std::get_if<MeshEnd>(&m)) {
      EXPECT_EQ(e->checksum, s.mesh.checksum());
    }
  }
  EXPECT_TRUE(begin_seen);
  EXPECT_EQ(r.link->counters().commits_sent, 1u);
}

TEST(StationLink, NoPeerStationGoesOnAndPeerWithSameVersionGetsNoFullMesh) {
  Rig r;
  r.wire.cut();
  for (int i = 0; i < 5; ++i) r.poll();
  EXPECT_FALSE(r.link->connected());
  r.wire.up = true;
  r.bridge_send(bridge_hello(1, r.station.mesh.checksum()));  // already holds version 1
  for (int i = 0; i < 10; ++i) r.poll();
  const auto got = r.bridge_receive();
  EXPECT_EQ(count(got, MessageType::mesh_begin), 0u);
  EXPECT_TRUE(r.link->peer_synced());
  // Asked explicitly: full mesh even when versions agree.
  r.bridge_send(ResendRequest{1, r.station.mesh.checksum()});
  for (int i = 0; i < 10; ++i) r.poll();
  EXPECT_EQ(count(r.bridge_receive(), MessageType::mesh_begin), 1u);
  EXPECT_EQ(r.link->counters().resend_requests, 1u);
}

TEST(StationLink, SlowPeerDropsLiveFramesButNeverHalfACommit) {
  Rig r;
  r.bridge_send(bridge_hello(0, 0));
  for (int i = 0; i < 50; ++i) r.poll();
  (void)r.bridge_receive();
  r.wire.capacity = 0;  // the peer stops reading
  Station& s = r.station;
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  for (int k = 1; k <= 2000; ++k) {
    s.hand(0, session::test_support::z_turn({0, 0, 0.0002 * k}, 0.0002 * k));
    (void)s.tick();
    r.poll();
  }
  EXPECT_GT(r.link->counters().live_dropped, 0u);
  s.button(kGrab0, false);
  (void)s.tick();
  r.poll();
  r.wire.capacity = std::size_t{1} << 23;
  for (int i = 0; i < 200; ++i) r.poll();
  const auto got = r.bridge_receive();
  // Either the commit set or (no room) a full mesh: in both cases a mesh_end with
  // the station's checksum, and every begin has its end.
  ASSERT_GE(count(got, MessageType::mesh_end), 1u);
  EXPECT_EQ(count(got, MessageType::mesh_begin), count(got, MessageType::mesh_end));
  std::uint64_t last = 0;
  for (const auto& m : got) {
    if (const auto* e = std::get_if<MeshEnd>(&m)) last = e->checksum;
  }
  EXPECT_EQ(last, s.mesh.checksum());
}

}  // namespace
}  // namespace twister::link
