// Replay with refinement on (issue 13): random stroke sequences (one or two hands,
// turns about any axis up to 170 degrees, drags, clutch steps, undo and redo) on a
// coarse box; the journal replayed into a fresh session gives the same mesh bit for
// bit, whatever that session's own refinement settings, also when the capacity ran
// out on the way; and the mesh stays a closed manifold.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <memory>

#include "mesh_checks.hpp"
#include "refine_harness.hpp"

namespace twister::input {
namespace {

using namespace test_support;
using twister::test_support::closed_manifold;

// U, V of the identity frame turned by `angle` about the unit `axis` (Rodrigues).
math::Frame turned(glm::dvec3 origin, glm::dvec3 axis, double angle) {
  const auto rot = [&](glm::dvec3 p) {
    return p * std::cos(angle) + glm::cross(axis, p) * std::sin(angle) +
           axis * glm::dot(axis, p) * (1.0 - std::cos(angle));
  };
  return math::frame_from_uv(origin, rot({1, 0, 0}), rot({0, 1, 0}));
}

glm::dvec3 any_point() {
  return {*rc::gen::inRange(-60, 61) / 100.0, *rc::gen::inRange(-60, 61) / 100.0,
          *rc::gen::inRange(-60, 61) / 100.0};
}

glm::dvec3 any_axis() {
  glm::dvec3 a(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101),
               *rc::gen::inRange(1, 101));
  return glm::normalize(a);
}

// One stroke of `mask` (1, 2 or 3): grab, move in a few steps, maybe a clutch step
// of hand 1, release (together or one after the other).
void random_stroke(RefineStation& s) {
  const auto mask = static_cast<std::uint8_t>(*rc::gen::inRange(1, 4));
  std::array<glm::dvec3, 2> from{any_point(), any_point()};
  if (glm::length(from[0] - from[1]) < 0.1) from[1] = -from[0] + glm::dvec3(0.2, 0, 0);
  std::array<glm::dvec3, 2> to{from[0] + 0.3 * any_point(), from[1] + 0.3 * any_point()};
  std::array<glm::dvec3, 2> axis{any_axis(), any_axis()};
  const std::array<double, 2> angle{*rc::gen::inRange(-170, 171) * std::numbers::pi / 180.0,
                                    *rc::gen::inRange(-170, 171) * std::numbers::pi / 180.0};
  const std::array<std::uint8_t, 2> grab{kGrab0, kGrab1};
  for (std::uint8_t h = 0; h < 2; ++h) {
    if ((mask & (1u << h)) == 0) continue;
    s.hand(h, math::identity_frame(from[h]));
    s.button(grab[h], true);
  }
  (void)s.tick();
  const bool clutch = (mask & 2u) != 0 && *rc::gen::inRange(0, 4) == 0;
  for (int k = 1; k <= 4; ++k) {
    for (std::uint8_t h = 0; h < 2; ++h) {
      if ((mask & (1u << h)) == 0) continue;
      const double t = k / 4.0;
      s.hand(h, turned(from[h] + t * (to[h] - from[h]), axis[h], t * angle[h]));
    }
    if (clutch && k == 2) s.button(kFreeze1, true);
    if (clutch && k == 3) s.button(kFreeze1, false);
    (void)s.tick();
  }
  const bool together = *rc::gen::inRange(0, 2) == 0;
  for (std::uint8_t h = 0; h < 2; ++h) {
    if ((mask & (1u << h)) == 0) continue;
    s.button(grab[h], false);
    if (!together) (void)s.tick();
  }
  (void)s.tick();
}

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
}  // namespace twister::input
