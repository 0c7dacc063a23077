// SceneReplica: full mesh, commits verified by checksum, resend on mismatch or on
// a commit for a version it does not hold; live stroke weights from the core plan.
#include <gtest/gtest.h>

#include <array>

#include "scene_replica.hpp"
#include "twister/link/math_conversion.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/screw.hpp"

namespace twister::bridge {
namespace {

// 3 x 3 grid at z = 0, spacing 0.1 m.
MeshData grid() {
  MeshData m;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      m.x.push_back(0.1F * static_cast<float>(i));
      m.y.push_back(0.1F * static_cast<float>(j));
      m.z.push_back(0.0F);
    }
  }
  for (std::uint32_t j = 0; j < 2; ++j) {
    for (std::uint32_t i = 0; i < 2; ++i) {
      const std::uint32_t a = 3 * j + i;
      m.indices.insert(m.indices.end(), {a, a + 1, a + 3, a + 1, a + 4, a + 3});
    }
  }
  return m;
}

std::vector<link::LinkMessage> mesh_messages(const MeshData& m, bool full, std::uint32_t base,
                                             std::uint32_t version, std::uint64_t checksum) {
  std::vector<link::LinkMessage> out(4);
  out[0] = link::MeshBegin{full, base, version, static_cast<std::uint32_t>(m.vertex_count()),
                           static_cast<std::uint32_t>(m.triangle_count())};
  auto& v = out[1].emplace<link::Vertices>();
  v.count = static_cast<std::uint16_t>(m.vertex_count());
  for (std::uint32_t i = 0; i < m.vertex_count(); ++i) v.items[i] = {i, m.x[i], m.y[i], m.z[i]};
  auto& t = out[2].emplace<link::Triangles>();
  t.first = 0;
  t.count = static_cast<std::uint16_t>(m.triangle_count());
  std::copy(m.indices.begin(), m.indices.end(), t.indices.begin());
  out[3] = link::MeshEnd{version, checksum};
  return out;
}

std::optional<link::ResendRequest> feed(SceneReplica& r, const std::vector<link::LinkMessage>& ms) {
  std::optional<link::ResendRequest> last;
  for (const auto& m : ms) {
    if (auto q = r.apply(m)) last = q;
  }
  return last;
}

// A replica holding grid() as version 1.
SceneReplica replica_with_grid() {
  SceneReplica r;
  const MeshData m = grid();
  (void)feed(r, mesh_messages(m, true, 0, 1, *mesh_checksum(m)));
  return r;
}

// The change set of a commit from version 1 to 2 of the grid that moves one vertex.
std::vector<link::LinkMessage> commit_messages(const link::VertexEntry& moved,
                                               std::uint64_t checksum) {
  std::vector<link::LinkMessage> commit(3);
  commit[0] = link::MeshBegin{false, 1, 2, 9, 8};
  auto& v = commit[1].emplace<link::Vertices>();
  v.count = 1;
  v.items[0] = moved;
  commit[2] = link::MeshEnd{2, checksum};
  return commit;
}

TEST(BridgeSceneReplica, FullMeshThenCommitIsVerified) {
  SceneReplica r;
  const MeshData m = grid();
  const std::uint64_t sum = *mesh_checksum(m);
  EXPECT_FALSE(feed(r, mesh_messages(m, true, 0, 1, sum)));
  ASSERT_TRUE(r.has_mesh());
  EXPECT_EQ(r.version(), 1u);
  EXPECT_EQ(r.checksum(), sum);
  // Commit: vertex 4 moves up.
  MeshData moved = m;
  moved.z[4] = 0.05F;
  EXPECT_FALSE(
      feed(r, commit_messages({4, moved.x[4], moved.y[4], moved.z[4]}, *mesh_checksum(moved))));
  EXPECT_EQ(r.version(), 2u);
  EXPECT_EQ(r.mesh().z[4], 0.05F);
  EXPECT_EQ(r.counters().commits, 1u);
}

TEST(BridgeSceneReplica, ChecksumMismatchKeepsTheVerifiedMeshAndAsksForResend) {
  SceneReplica r = replica_with_grid();
  // 0xdeadbeef: not the checksum of the result.
  const auto request = feed(r, commit_messages({4, 0.1F, 0.1F, 0.05F}, 0xdeadbeefULL));
  ASSERT_TRUE(request);
  EXPECT_EQ(request->have_version, 1u);
  EXPECT_EQ(r.version(), 1u);
  EXPECT_EQ(r.mesh().z[4], 0.0F);  // unchanged
  EXPECT_EQ(r.counters().checksum_mismatches, 1u);
  // The resend brings the station's mesh: accepted.
  MeshData moved = grid();
  moved.z[4] = 0.05F;
  EXPECT_FALSE(feed(r, mesh_messages(moved, true, 0, 2, *mesh_checksum(moved))));
  EXPECT_EQ(r.version(), 2u);
}

TEST(BridgeSceneReplica, CommitForAnotherVersionAndBadIndicesAskForResend) {
  SceneReplica r = replica_with_grid();
  const link::MeshBegin gap{false, 5, 6, 9, 8};  // missed versions 2..5
  EXPECT_TRUE(r.apply(gap));
  EXPECT_EQ(r.counters().version_gaps, 1u);
  // A full mesh whose triangle points past the vertices is refused.
  MeshData bad = grid();
  bad.indices[0] = 99;
  EXPECT_TRUE(feed(r, mesh_messages(bad, true, 0, 7, 0)));
  EXPECT_EQ(r.version(), 1u);
}

// Protocol 2: the stroke's exact start frames once, then compact end poses (the
// bridge rebuilds the screws); same intent as with protocol 1's screws.
TEST(BridgeSceneReplica, LiveStrokeWeightsAndCpuWarp) {
  SceneReplica r = replica_with_grid();
  const std::array<math::Frame, 2> start{math::identity_frame({0.1, 0.1, 0.0}), math::Frame{}};
  const std::array<math::Frame, 2> end{math::identity_frame({0.1, 0.1, 0.04}), math::Frame{}};
  LiveMessages live = make_live_messages(1, 1, math::WarpMethod::twister, 0.12, 1, start, end);
  (void)r.apply(live.stroke);
  (void)r.apply(live.hands);
  ASSERT_TRUE(r.live().active);
  EXPECT_FLOAT_EQ(r.live().weight1[4], 1.0F);  // the grab point itself
  EXPECT_EQ(r.live().weight1[0], 0.0F);        // corner: 0.141 m away, outside the radius
  EXPECT_GT(r.live().weight1[1], 0.0F);        // edge middle: 0.1 m away, inside
  const MeshData warped = r.cpu_warp();
  ASSERT_EQ(warped.vertex_count(), 9u);
  EXPECT_NEAR(warped.z[4], 0.04F, 1e-6F);
  // A stroke for another mesh version is not drawn.
  live = make_live_messages(7, 2, math::WarpMethod::twister, 0.12, 1, start, end);
  (void)r.apply(live.stroke);
  (void)r.apply(live.hands);
  EXPECT_FALSE(r.live().active);
  EXPECT_EQ(r.counters().live_stale, 1u);
}

}  // namespace
}  // namespace twister::bridge
