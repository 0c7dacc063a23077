// Replay with refinement on (issue 13): random stroke sequences (one or two hands,
// turns about any axis up to 170 degrees, drags, clutch steps, undo and redo) on a
// coarse box; the journal replayed into a fresh session gives the same mesh bit for
// bit, whatever that session's own refinement settings, also when the capacity ran
// out on the way; and the mesh stays a closed manifold.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <memory>

#include "mesh_checks.hpp"
#include "refine_harness.hpp"
#include "refine_random.hpp"

namespace twister::session {
namespace {

using namespace test_support;
using twister::test_support::closed_manifold;

RC_GTEST_PROP(RefineReplay, JournalReplaysBitIdenticallyWithRefinementOn, ()) {
  const double threshold = *rc::gen::element(0.004, 0.01, 0.03);
  const auto spare = static_cast<std::size_t>(*rc::gen::element(200, 2'000, 12'000));
  RefineStation live(3, spare, refine_config(threshold));
  const int strokes = *rc::gen::inRange(1, 6);
  for (int i = 0; i < strokes; ++i) {
    random_stroke(live);
    const int history = *rc::gen::inRange(0, 6);
    if (history == 0) (void)live.session->undo();
    if (history == 1 && live.session->undo().ok()) RC_ASSERT(live.session->redo().ok());
  }
  RC_ASSERT(closed_manifold(live.mesh()));
  RC_TAG(live.session->state().refine.last_stop == mesh::RefineStop::done ? "within threshold"
                                                                          : "at capacity");
  // The replaying session's own settings do not matter: the journal has the threshold.
  RefineStation replayed(3, spare, refine_config(0.05, false), false);
  journal::JournalReader reader(live.storage);
  RC_ASSERT(reader.open().ok());
  const auto n = replayed.session->replay(reader);
  RC_ASSERT(n.ok());
  RC_ASSERT(*n == live.session->next_sequence());
  RC_ASSERT(replayed.mesh().checksum() == live.mesh().checksum());
  RC_ASSERT(replayed.session->history().undo_depth() == live.session->history().undo_depth());
}

TEST(RefineReplay, AFinerStartMeshTakesTheSameStrokes) {
  RefineStation coarse(3, 12'000, refine_config(0.004));
  (void)twist_box(coarse, 2.5);
  RefineStation fine(5, 12'000, refine_config(0.004), false);  // holds every coarse vertex
  journal::JournalReader reader(coarse.storage);
  ASSERT_TRUE(reader.open().ok());
  ASSERT_TRUE(fine.session->replay(reader).ok());
  EXPECT_GT(fine.mesh().vertex_count(), meshio::box_vertices(5));
  EXPECT_TRUE(closed_manifold(fine.mesh()));
  // The coarse box's corners and face centres are lattice points of the finer one.
  meshio::MeshBuffer coarse_rest(26, 48),
      fine_rest(meshio::box_vertices(5), meshio::box_triangles(5));
  ASSERT_TRUE(meshio::make_box(coarse_rest.mesh(), 3, 0.5f).ok());
  ASSERT_TRUE(meshio::make_box(fine_rest.mesh(), 5, 0.5f).ok());
  int matched = 0;
  for (std::uint32_t c = 0; c < 26; ++c) {
    for (std::uint32_t f = 0; f < fine_rest.mesh().vertex_count(); ++f) {
      if (fine_rest.mesh().position(f) != coarse_rest.mesh().position(c)) continue;
      EXPECT_LT(glm::length(fine.mesh().position(f) - coarse.mesh().position(c)), 1e-5f);
      ++matched;
    }
  }
  EXPECT_EQ(matched, 26);
}

}  // namespace
}  // namespace twister::session
