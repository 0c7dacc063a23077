// Refinement at commit through the session (issue 13): the acceptance twist of a
// coarse box by 170 degrees meets the threshold on every edge against the
// double-precision warp and stays a closed manifold; at capacity the commit stands,
// refinement stops conforming and says why; undo/redo restore the topology; freeze
// steps are not refined (a chain's end is); the journal records the threshold; no allocation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "allocation_counter.hpp"
#include "mesh_checks.hpp"
#include "refine_harness.hpp"
#include "twister/mesh/mesh_refiner.hpp"
#include "twister/mesh/vertex_normals.hpp"
#include "twister/session/plan_warp.hpp"

namespace twister::session {
namespace {

using namespace test_support;
using twister::test_support::closed_manifold;
using twister::test_support::max_midpoint_error;

const double kTurn170 = 170.0 * std::numbers::pi / 180.0;

std::vector<journal::JournalRecord> records_of(RefineStorage& storage) {
  journal::JournalReader reader(storage);
  EXPECT_TRUE(reader.open().ok());
  std::vector<journal::JournalRecord> out;
  for (auto r = reader.next(); r.ok(); r = reader.next()) out.push_back(*r);
  return out;
}

// The plan a replay builds for a chain-step-0 stroke record, on `rest`.
void build_plan(math::WarpPlan& plan, const mesh::Mesh& rest, const journal::StrokeRecord& s) {
  std::array<math::Frame, 2> start{}, end{};
  std::size_t n = 0;
  std::uint8_t turns = 0;
  for (std::uint8_t h = 0; h < 2; ++h) {
    if ((s.hand_mask & (1u << h)) == 0) continue;
    start[n] = s.start[h];
    end[n] = s.end[h];
    if ((s.long_turns & (1u << h)) != 0) turns = static_cast<std::uint8_t>(turns | (1u << n));
    ++n;
  }
  ASSERT_TRUE(plan.build({rest.x(), rest.y(), rest.z()}, std::span(start).first(n), s.radius_m,
                         static_cast<math::WarpMethod>(s.method))
                  .ok());
  ASSERT_TRUE(plan.update_turns(std::span(end).first(n), turns).ok());
}

TEST(RefineCommit, CoarseBoxTwisted170DegreesHasEveryEdgeWithinTheThreshold) {
  constexpr double kThreshold = 0.002;
  RefineStation s(3, 15'000, refine_config(kThreshold));
  meshio::MeshBuffer rest(kRefineVertices, kRefineTriangles);
  ASSERT_TRUE(rest.mesh().copy_from(s.mesh()).ok());
  const SessionEvents events = twist_box(s, kTurn170);
  const SessionEvent* refined = find_event(events, SessionEventKind::refined);
  ASSERT_NE(refined, nullptr);
  EXPECT_EQ(find_event(events, SessionEventKind::refine_stopped), nullptr);
  EXPECT_EQ(refined->refinement().sequence, 0u);
  EXPECT_TRUE(closed_manifold(s.mesh()));
  EXPECT_EQ(s.mesh().vertex_count(),
            26u + static_cast<std::size_t>(refined->refinement().vertices_added));

  // The journal says how it was refined; the same refinement done here on the rest
  // mesh gives the session's topology, the threshold met on every edge against the
  // double-precision warp, and the new vertices where the warp takes their midpoints.
  const auto records = records_of(s.storage);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].stroke.refine_threshold_m, kThreshold);
  auto plan = std::make_unique<math::WarpPlanWithStorage<kRefineVertices>>();
  build_plan(*plan, rest.mesh(), records[0].stroke);
  const PlanWarp warp(*plan);
  const double before = max_midpoint_error(rest.mesh(), warp);
  auto refiner =
      std::make_unique<mesh::MeshRefinerWithStorage<kRefineVertices, kRefineTriangles>>();
  const auto result = refiner->refine(rest.mesh(), warp, kThreshold);
  ASSERT_TRUE(result.ok());
  const double after = max_midpoint_error(rest.mesh(), warp);
  EXPECT_LE(after, kThreshold);
  ASSERT_EQ(rest.mesh().vertex_count(), s.mesh().vertex_count());
  ASSERT_EQ(rest.mesh().triangle_count(), s.mesh().triangle_count());
  EXPECT_TRUE(std::equal(rest.mesh().triangle_indices().begin(),
                         rest.mesh().triangle_indices().end(),
                         s.mesh().triangle_indices().begin()));
  for (std::uint32_t v = 26; v < s.mesh().vertex_count(); ++v) {
    EXPECT_EQ(s.mesh().position(v), glm::vec3(warp.warp(glm::dvec3(rest.mesh().position(v)))));
  }
  std::printf(
      "170-degree twist of a 26-vertex box, threshold %g m: %u edges split, %zu -> %zu "
      "vertices, %zu triangles; max midpoint error %.4g m before, %.6g m after\n",
      kThreshold, result->edges_split, std::size_t{26}, s.mesh().vertex_count(),
      s.mesh().triangle_count(), before, after);
  EXPECT_EQ(s.session->state().refine.last_vertices_added, result->edges_split);
}

TEST(RefineCommit, AtCapacityTheCommitAppliesAndRefinementStopsConforming) {
  RefineStation s(3, 40, refine_config(0.001));
  const glm::vec3 corner = s.mesh().position(25);  // (0.5, 0.5, 0.5), on the turning hand
  const SessionEvents events = twist_box(s, kTurn170);
  const SessionEvent* committed = find_event(events, SessionEventKind::committed);
  ASSERT_NE(committed, nullptr);
  EXPECT_TRUE(committed->status.ok());
  const SessionEvent* stopped = find_event(events, SessionEventKind::refine_stopped);
  ASSERT_NE(stopped, nullptr);
  EXPECT_EQ(stopped->refinement_stop().stop, mesh::RefineStop::vertex_capacity);
  EXPECT_EQ(stopped->status.code(), StatusCode::resource_exhausted);
  EXPECT_EQ(find_event(events, SessionEventKind::refined)->refinement().vertices_added, 40u);
  EXPECT_EQ(s.mesh().vertex_count(), s.mesh().vertex_capacity());
  EXPECT_TRUE(closed_manifold(s.mesh()));
  EXPECT_GT(glm::length(s.mesh().position(25) - corner), 0.3f);  // the warp applied
  const RefineStatus st = s.session->state().refine;
  EXPECT_EQ(st.last_stop, mesh::RefineStop::vertex_capacity);
  EXPECT_EQ(st.spare_vertices, 0u);
  // The next commit still applies; with no room left it adds nothing and says so.
  const SessionEvents again = twist_box(s, -0.5);
  EXPECT_TRUE(find_event(again, SessionEventKind::committed)->status.ok());
  EXPECT_EQ(find_event(again, SessionEventKind::refined)->refinement().vertices_added, 0u);
  EXPECT_NE(find_event(again, SessionEventKind::refine_stopped), nullptr);
  EXPECT_TRUE(closed_manifold(s.mesh()));
}

TEST(RefineCommit, UndoAndRedoRestoreTheTopologyBitIdentically) {
  RefineStation s(3, 15'000, refine_config(0.003));
  const std::uint64_t initial = s.mesh().checksum();
  (void)twist_box(s, kTurn170);
  const std::uint64_t first = s.mesh().checksum();
  const std::size_t first_vertices = s.mesh().vertex_count();
  (void)twist_box(s, -1.0);
  const std::uint64_t second = s.mesh().checksum();
  ASSERT_GT(s.mesh().vertex_count(), first_vertices);
  ASSERT_TRUE(s.session->undo().ok());
  EXPECT_EQ(s.mesh().checksum(), first);
  ASSERT_TRUE(s.session->undo().ok());
  EXPECT_EQ(s.mesh().checksum(), initial);
  EXPECT_EQ(s.mesh().vertex_count(), 26u);
  ASSERT_TRUE(s.session->redo().ok());
  ASSERT_TRUE(s.session->redo().ok());
  EXPECT_EQ(s.mesh().checksum(), second);
  EXPECT_TRUE(closed_manifold(s.mesh()));
}

TEST(RefineCommit, OffMeansUnrefinedAndVersionOneRecords) {
  RefineStation s(3, 1'000, refine_config(0.001, false));
  const SessionEvents events = twist_box(s, kTurn170);
  EXPECT_EQ(find_event(events, SessionEventKind::refined), nullptr);
  EXPECT_EQ(s.mesh().vertex_count(), 26u);
  EXPECT_EQ(records_of(s.storage).at(0).stroke.refine_threshold_m, 0.0);
}

TEST(RefineCommit, FreezeStepsAreNotRefinedTheChainsEndIs) {
  RefineStation s(3, 15'000, refine_config(0.002));
  s.hand(1, math::identity_frame({0, 0, 0.5}));
  s.button(kGrab1, true);
  (void)s.tick();
  s.hand(1, z_turn({0, 0, 0.5}, 1.5));
  (void)s.tick();
  s.button(kFreeze1, true);
  (void)s.tick();
  EXPECT_EQ(s.mesh().vertex_count(), 26u);  // the freeze step (chain step 0): not refined
  s.button(kFreeze1, false);
  (void)s.tick();
  s.hand(1, z_turn({0, 0, 0.5}, 2.5));
  (void)s.tick();
  s.button(kGrab1, false);
  (void)s.tick();
  // The chain's end (step 1): refined under the chain's combined warp.
  const std::size_t after_chain = s.mesh().vertex_count();
  EXPECT_GT(after_chain, 26u);
  EXPECT_EQ(s.session->state().refine.refined_chains, 1u);
  (void)twist_box(s, 1.0);
  EXPECT_GT(s.mesh().vertex_count(), after_chain);
  const auto records = records_of(s.storage);
  ASSERT_EQ(records.size(), 3u);
  EXPECT_EQ(records[0].stroke.refine_threshold_m, 0.0);
  EXPECT_EQ(records[1].stroke.chain_step, 1u);
  EXPECT_EQ(records[1].stroke.refine_threshold_m, 0.002);
  EXPECT_EQ(records[2].stroke.refine_threshold_m, 0.002);
  EXPECT_TRUE(closed_manifold(s.mesh()));
}

TEST(RefineCommit, ReplayWithoutRefinementMemoryRefusesARefinedRecord) {
  RefineStation live(3, 2'000, refine_config(0.004));
  (void)twist_box(live, kTurn170);
  auto mesh = std::make_unique<TestMesh>();
  make_grid(*mesh, 9);
  const std::uint64_t before = mesh->checksum();
  // A session without refinement storage (kTriangles = 0).
  auto plain = std::make_unique<SculptSessionWithStorage<kVertices, kVertices, 1024, 8>>(
      test_config(), *mesh, nullptr);
  EXPECT_EQ(plain->apply_record(records_of(live.storage).at(0)).code(),
            StatusCode::failed_precondition);
  EXPECT_EQ(plain->next_sequence(), 0u);
  EXPECT_EQ(mesh->checksum(), before);
}

// The session keeps vertex normals of the refined mesh: after the commit, undo, redo.
TEST(RefineCommit, NormalsFollowEveryChangeOfTheModel) {
  RefineStation s(3, 15'000, refine_config(0.003));
  const auto same = [&s] {
    std::vector<float> x(s.mesh().vertex_count()), y(x.size()), z(x.size());
    EXPECT_TRUE(mesh::compute_vertex_normals(s.mesh(), {x, y, z}).ok());
    const mesh::NormalColumns n = s.session->normals();
    return n.x.size() == x.size() && std::equal(x.begin(), x.end(), n.x.begin()) &&
           std::equal(y.begin(), y.end(), n.y.begin()) &&
           std::equal(z.begin(), z.end(), n.z.begin());
  };
  EXPECT_TRUE(same());
  (void)twist_box(s, kTurn170);
  ASSERT_GT(s.mesh().vertex_count(), 26u);
  EXPECT_TRUE(same());
  ASSERT_TRUE(s.session->undo().ok());
  EXPECT_TRUE(same());
  ASSERT_TRUE(s.session->redo().ok());
  EXPECT_TRUE(same());
}

TEST(RefineCommit, ARefinedCommitDoesNotAllocate) {
  RefineStation s(3, 15'000, refine_config(0.002));
  (void)twist_box(s, 0.3);  // first-use set-up of everything
  EXPECT_NO_ALLOCATIONS({ (void)twist_box(s, kTurn170); });
  EXPECT_GT(s.session->state().refine.last_vertices_added, 0u);
}

}  // namespace
}  // namespace twister::session
