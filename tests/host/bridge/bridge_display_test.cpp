// Issue 14, link part (label display): a real SculptSession behind StationLink and a
// headless BridgeApp on an in-memory wire.
//   - station-warp == bridge-warp: the bridge rebuilds the screws from the stroke's
//     exact start frames and the compact end poses and warps as the station does,
//     for one and two hands and at a half turn in either sense (the station keeps
//     the axis sense there; the bridge follows the sense it is sent);
//   - the SceneReplica display API: hands (pose, tracked, buttons) whether or not
//     they grab, the radius, the object pose after a one-hand move, the status;
//   - a commit that rewrites triangles in place is a change set, not a full mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bridge_link_rig.hpp"
#include "twister/link/math_conversion.hpp"

namespace twister::bridge {
namespace {

using test_support::warp_difference;

using session::test_support::kGrab1;
using session::test_support::kMove0;
using session::test_support::kRadius0;
using session::test_support::Station;

struct Rig : test_support::BridgeLinkRig {
  Rig() : BridgeLinkRig(null_log) {}
  static inline ports::NullLogSink null_log;
  void step(int rounds = 2) {
    (void)station.tick();
    run(rounds);
  }
};

TEST(BridgeDisplay, StationWarpEqualsBridgeWarpForOneAndTwoHands) {
  Rig r;
  r.run();
  Station& s = r.station;
  s.hand(0, math::identity_frame({-0.5, 0, 0}));
  s.hand(1, math::identity_frame({0.5, 0, 0}));
  s.button(session::test_support::kGrab0, true);
  r.step();
  for (int k = 1; k <= 4; ++k) {
    s.hand(0, session::test_support::z_turn({-0.5, 0.02 * k, 0.05 * k}, 0.3 * k));
    r.step();
    const double d = warp_difference(r);
    EXPECT_GE(d, 0.0);
    EXPECT_LT(d, 2e-5) << "one hand, step " << k;
  }
  s.button(kGrab1, true);  // the second hand joins: a two-hand segment
  r.step();
  for (int k = 1; k <= 4; ++k) {
    s.hand(0, session::test_support::z_turn({-0.5 - 0.03 * k, 0.1, 0.2}, 1.2 + 0.2 * k));
    s.hand(1, session::test_support::z_turn({0.5 + 0.03 * k, 0.0, -0.05 * k}, -0.25 * k));
    r.step();
    const double d = warp_difference(r);
    EXPECT_GE(d, 0.0);
    EXPECT_LT(d, 2e-5) << "two hands, step " << k;
  }
  EXPECT_EQ(r.bridge.replica().live().hands.size(), 2u);
  EXPECT_EQ(r.bridge.replica().counters().live_missed, 0u);
}

// At exactly a half turn the minimal screw's axis sense is ambiguous; the station
// keeps the sense of the previous update. The bridge must turn the same way.
TEST(BridgeDisplay, StationWarpEqualsBridgeWarpAtAHalfTurnInEitherSense) {
  for (const double sense : {1.0, -1.0}) {
    Rig r;
    r.run();
    Station& s = r.station;
    const glm::dvec3 grab(0.0, 0.0, 0.0);
    s.hand(0, math::identity_frame(grab));
    s.button(session::test_support::kGrab0, true);
    r.step();
    for (const double a : {0.5, 0.9, 0.99, 0.999999, 1.0}) {
      s.hand(0, session::test_support::z_turn(grab, sense * a * std::numbers::pi));
      r.step();
      const double d = warp_difference(r);
      ASSERT_GE(d, 0.0);
      EXPECT_LT(d, 2e-5) << "turn " << sense * a << " pi";
    }
    const math::Screw& station = s.session->live().plan->screw(0);
    const math::Screw& bridge = r.bridge.replica().live().hands[0].screw;
    EXPECT_GT(glm::dot(station.axis, bridge.axis), 0.99) << "sense " << sense;
  }
}

// The sense survives float rounding of the end pose just short of a half turn.
TEST(BridgeDisplay, LiveScrewKeepsTheStationsSenseThroughFloatRounding) {
  const math::Frame start = math::frame_from_uv({0.1, 0.2, 0.3}, {1, 0, 0}, {0, 1, 0});
  for (const double eps : {1e-4, 1e-7, 1e-9, 1e-12, 0.0}) {
    for (const double sense : {1.0, -1.0}) {
      const math::Frame end =
          session::test_support::z_turn({0.15, 0.25, 0.3}, sense * (std::numbers::pi - eps));
      const math::Screw station = math::compute_screw(start, end, glm::dvec3(0, 0, sense));
      const link::CompactPose sample = link::to_live_compact(start, end, station);
      const math::Frame rebuilt = link::live_end_frame(start, sample);
      const math::Screw bridge = link::live_screw(start, rebuilt, sample);
      const glm::dvec3 p(0.4, -0.2, 0.3);
      const glm::dvec3 a = math::screw_at(station, 0.5, p);
      const glm::dvec3 b = math::screw_at(bridge, 0.5, p);
      EXPECT_LT(glm::length(a - b), 1e-5) << "eps " << eps << " sense " << sense;
    }
  }
}

TEST(BridgeDisplay, ReplicaShowsHandsButtonsRadiusObjectAndStatusWithoutAGrab) {
  Rig r;
  r.run();
  Station& s = r.station;
  const math::Frame pose = session::test_support::z_turn({0.3, -0.2, 0.1}, 0.4);
  s.hand(0, pose);
  s.button(kRadius0, true);
  r.step();
  const SceneReplica& rep = r.bridge.replica();
  const HandView& h = rep.hands()[0];
  ASSERT_TRUE(h.present);
  EXPECT_TRUE(h.tracked);
  EXPECT_FALSE(h.in_stroke);
  EXPECT_TRUE(h.radius);
  EXPECT_FALSE(h.grab);
  EXPECT_FALSE(rep.hands()[1].present);
  EXPECT_NEAR(glm::length(h.pose.origin - pose.origin), 0.0, 1e-6);
  EXPECT_NEAR(glm::length(h.pose.u - pose.u), 0.0, 1e-6);
  EXPECT_FLOAT_EQ(rep.radius_m(), s.session->radius_m());
  // The hand moves without grabbing: updates at the tracker rate.
  const std::uint64_t before = rep.counters().live_frames;
  for (int k = 1; k <= 5; ++k) {
    s.hand(0, session::test_support::z_turn({0.3, -0.2 + 0.01 * k, 0.1}, 0.4));
    r.step();
  }
  EXPECT_EQ(rep.counters().live_frames - before, 5u);
  EXPECT_NEAR(rep.hands()[0].pose.origin.y, -0.15, 1e-6);
  // A one-hand object move: the object pose follows on the display.
  s.button(kRadius0, false);
  s.button(kMove0, true);
  r.step();
  s.hand(0, session::test_support::z_turn({0.35, -0.1, 0.2}, 0.7));
  r.step();
  s.button(kMove0, false);
  r.step();
  const math::Frame& object = s.session->object_pose();
  EXPECT_GT(glm::length(object.origin), 0.01);
  EXPECT_NEAR(glm::length(rep.object_pose().origin - object.origin), 0.0, 1e-6);
  EXPECT_NEAR(glm::length(rep.object_pose().v - object.v), 0.0, 1e-6);
  ASSERT_TRUE(rep.has_status());
  const link::StatusReport& st = rep.station_status();
  EXPECT_EQ(st.mesh_version, r.link->mesh_version());
  EXPECT_EQ(st.vertex_count, s.mesh.vertex_count());
  EXPECT_EQ(st.vertex_capacity, s.mesh.vertex_capacity());
  EXPECT_EQ(st.triangle_capacity, s.mesh.triangle_capacity());
  EXPECT_EQ(st.strokes.not_saved, 0u);
}

// The refinement engineer's edge splits rewrite triangles and append some: the
// commit carries them as runs of triangles, and the display's checksum agrees.
TEST(BridgeDisplay, CommitWithRewrittenTrianglesIsAChangeSetNotAFullMesh) {
  Rig r;
  r.run();
  ASSERT_EQ(r.bridge.replica().counters().full_meshes, 1u);
  r.stroke(0.05);
  // At the commit, split: rotate the corners of triangles 10..19 and append two.
  mesh::Mesh& m = r.station.mesh;
  std::vector<std::uint32_t> idx(m.triangle_indices().begin(), m.triangle_indices().end());
  std::vector<glm::vec3> pos;
  for (std::uint32_t i = 0; i < m.vertex_count(); ++i) pos.push_back(m.position(i));
  for (std::size_t t = 10; t < 20; ++t) std::rotate(&idx[3 * t], &idx[3 * t + 1], &idx[3 * t + 3]);
  m.clear();
  for (const glm::vec3& p : pos) (void)m.add_vertex(p);
  for (std::size_t t = 0; 3 * t < idx.size(); ++t) {
    (void)m.add_triangle(idx[3 * t], idx[3 * t + 1], idx[3 * t + 2]);
  }
  (void)m.add_triangle(0, 2, 1);
  (void)m.add_triangle(3, 5, 4);
  r.run();
  const SceneReplica& rep = r.bridge.replica();
  EXPECT_EQ(rep.counters().full_meshes, 1u);
  EXPECT_EQ(rep.counters().commits, 1u);
  EXPECT_EQ(r.link->counters().full_sends, 1u);
  EXPECT_EQ(rep.checksum(), r.station.mesh.checksum());
  EXPECT_EQ(rep.mesh().triangle_count(), r.station.mesh.triangle_count());
}

}  // namespace
}  // namespace twister::bridge
