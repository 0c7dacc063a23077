// Issue 11 item 7 (label integrity): counts a peer announces are checked against
// the replica's limits before anything is allocated. A CRC-valid mesh_begin with
// counts 0xFFFFFFFF (it ended twister-bridge with std::bad_alloc), or 100 M
// vertices (1.25 GB held), is refused with no allocation at all, counted and
// logged; the bridge goes on and takes the next good mesh.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "allocation_counter.hpp"
#include "bridge_app.hpp"
#include "fakes/fake_clock.hpp"
#include "fakes/memory_wire.hpp"
#include "scene_replica.hpp"
#include "twister/link/link_codec.hpp"

namespace twister::bridge {
namespace {

template <link::LinkBody M>
std::vector<std::byte> frame(const M& m) {
  std::vector<std::byte> f(link::kMaxFrameBytes);
  const auto n = link::encode_frame(m, f);
  EXPECT_TRUE(n.ok());
  f.resize(n.ok() ? *n : 0);
  return f;
}

link::MeshBegin begin(bool full, std::uint32_t vertices, std::uint32_t triangles) {
  link::MeshBegin m;
  m = {full, 0, 1, vertices, triangles};
  return m;
}

TEST(ReplicaCapacity, HugeAnnouncedCountsAreRefusedWithoutAllocating) {
  SceneReplica replica;
  link::LinkDecoder decoder;
  for (const auto& m : {begin(true, 0xFFFFFFFFu, 0xFFFFFFFFu), begin(false, 0xFFFFFFFFu, 0),
                        begin(true, 100'000'000u, 10), begin(true, 10, 100'000'000u)}) {
    const std::vector<std::byte> bytes = frame(m);
    const link::LinkMessage* got = nullptr;
    for (const std::byte b : bytes) {
      if (const auto r = decoder.process(b); r.ok()) got = *r;
    }
    ASSERT_NE(got, nullptr);
    std::optional<link::ResendRequest> request;
    EXPECT_NO_ALLOCATIONS(request = replica.apply(*got));
    EXPECT_FALSE(request);  // a resend would bring the same mesh
    // Chunks of the refused set are ignored, also without allocating.
    link::Vertices v;
    v.count = 1;
    v.items[0] = {0xFFFFFFF0u, 1.0F, 2.0F, 3.0F};
    EXPECT_NO_ALLOCATIONS((void)replica.apply(v));
  }
  EXPECT_EQ(replica.counters().over_capacity, 4u);
  EXPECT_FALSE(replica.has_mesh());
  // Exactly at the limits is accepted.
  SceneReplica small(ReplicaLimits{3, 1});
  EXPECT_FALSE(small.apply(begin(true, 3, 1)));
  link::Triangles t;
  t.count = 1;
  t.indices[0] = 0;
  t.indices[1] = 1;
  t.indices[2] = 2;
  EXPECT_FALSE(small.apply(t));
  MeshData m;
  m.x = {0, 1, 0};
  m.y = {0, 0, 1};
  m.z = {0, 0, 0};
  m.indices = {0, 1, 2};
  link::MeshEnd e;
  e = {1, *mesh_checksum(m)};
  link::Vertices v;
  v.count = 3;
  for (std::uint32_t i = 0; i < 3; ++i) v.items[i] = {i, m.x[i], m.y[i], m.z[i]};
  EXPECT_FALSE(small.apply(v));
  EXPECT_FALSE(small.apply(e));
  EXPECT_TRUE(small.has_mesh());
  EXPECT_EQ(small.counters().over_capacity, 0u);
}

// The whole display: the 0xFFFFFFFF mesh_begin arrives over the link after the
// handshake; BridgeApp logs it and keeps running.
TEST(ReplicaCapacity, BridgeAppSurvivesAndLogsTheRefusal) {
  test::MemoryWire wire;
  test::MemoryLinkEnd station(wire, true);
  test::MemoryLinkEnd display(wire, false);
  struct Recorder final : ports::LogSink {
    int errors = 0;
    bool do_enabled(ports::LogLevel) const override { return true; }
    void do_write(ports::LogLevel level, const char*, const char*,
                  std::span<const ports::LogArg>) override {
      errors += level == ports::LogLevel::error ? 1 : 0;
    }
  } log;
  twister::test::FakeClock clock;
  BridgeApp app(display, clock, nullptr, {}, log);
  app.step();  // connects and says hello
  link::Hello hello;
  hello.role = link::Role::station;
  std::vector<std::byte> bytes = frame(hello);
  const auto huge = frame(begin(true, 0xFFFFFFFFu, 0xFFFFFFFFu));
  bytes.insert(bytes.end(), huge.begin(), huge.end());
  ASSERT_EQ(*station.send(bytes), bytes.size());
  app.step();
  EXPECT_TRUE(app.ready());
  EXPECT_EQ(app.replica().counters().over_capacity, 1u);
  EXPECT_EQ(log.errors, 1);
  EXPECT_EQ(app.stopped(), BridgeStop::none);
}

}  // namespace
}  // namespace twister::bridge
