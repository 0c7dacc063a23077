// Local refinement (issue 24): MeshRefiner::refine_around, over the triangles a stroke's
// weights touch, against the whole-mesh MeshRefiner::refine with the real warp of a
// random plan (one or two hands, any axis, up to 170 degrees, drags), on random meshes
// (box, sphere, grid, jittered or not), at random thresholds and capacities, for a
// few strokes in a row (the adjacency persists between calls): the same splits and
// the same bits whenever every edge over the threshold at the start has a triangle in
// the region; always a conforming mesh with every region edge within the threshold.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "allocation_counter.hpp"
#include "mesh_checks.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/mesh/mesh_refiner.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/refiner_buffer.hpp"
#include "twister/session/plan_warp.hpp"

namespace twister::session {
namespace {

using test_support::edge_incidence;

math::Frame turned(glm::dvec3 origin, glm::dvec3 axis, double angle) {
  const auto rot = [&](glm::dvec3 p) {
    return p * std::cos(angle) + glm::cross(axis, p) * std::sin(angle) +
           axis * glm::dot(axis, p) * (1.0 - std::cos(angle));
  };
  return math::frame_from_uv(origin, rot({1, 0, 0}), rot({0, 1, 0}));
}

glm::dvec3 any_point(double scale) {
  return scale * glm::dvec3(*rc::gen::inRange(-100, 101) / 100.0,
                            *rc::gen::inRange(-100, 101) / 100.0,
                            *rc::gen::inRange(-100, 101) / 100.0);
}

glm::dvec3 any_axis() {
  const glm::dvec3 a(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101),
                     *rc::gen::inRange(1, 101));
  return glm::normalize(a);
}

std::unique_ptr<meshio::MeshBuffer> any_mesh(std::size_t spare) {
  const int kind = *rc::gen::inRange(0, 3);
  const auto n = static_cast<std::size_t>(*rc::gen::inRange(3, 14));
  std::unique_ptr<meshio::MeshBuffer> b;
  if (kind == 0) {
    b = std::make_unique<meshio::MeshBuffer>(meshio::box_vertices(n) + spare,
                                             meshio::box_triangles(n) + 2 * spare);
    RC_ASSERT(meshio::make_box(b->mesh(), n, 0.3f).ok());
  } else if (kind == 1) {
    b = std::make_unique<meshio::MeshBuffer>(meshio::sphere_vertices(n, 2 * n) + spare,
                                             meshio::sphere_triangles(n, 2 * n) + 2 * spare);
    RC_ASSERT(meshio::make_sphere(b->mesh(), n, 2 * n, 0.3f).ok());
  } else {
    b = std::make_unique<meshio::MeshBuffer>(meshio::grid_vertices(n) + spare,
                                             meshio::grid_triangles(n) + 2 * spare);
    RC_ASSERT(meshio::make_grid(b->mesh(), n, 0.3f).ok());
  }
  if (*rc::gen::inRange(0, 2) == 0) {  // jitter: no ties in edge lengths
    mesh::Mesh& m = b->mesh();
    for (std::uint32_t v = 0; v < m.vertex_count(); ++v) {
      m.set_position(v, m.position(v) + glm::vec3(any_point(0.004)));
    }
  }
  if (*rc::gen::inRange(0, 3) == 0) {  // inconsistent winding: some triangles turned over
    RC_TAG("inconsistent winding");
    mesh::Mesh& m = b->mesh();
    for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
      if (*rc::gen::inRange(0, 4) != 0) continue;
      const auto tv = m.triangle(t);
      m.set_triangle(t, {tv[0], tv[2], tv[1]});
    }
  }
  return b;
}

// A random one- or two-hand stroke: start and end frames, radius.
struct StrokeDraw {
  math::PlanFrames start;
  math::PlanFrames end;
  double radius = 0.1;
};

StrokeDraw any_stroke() {
  StrokeDraw d;
  const int hands = *rc::gen::inRange(1, 3);
  d.radius = *rc::gen::inRange(5, 80) / 100.0;
  for (int h = 0; h < hands; ++h) {
    const glm::dvec3 from = any_point(0.35);
    d.start.push_back(math::identity_frame(from)).ignore();
    const double angle = *rc::gen::inRange(-170, 171) * std::numbers::pi / 180.0;
    d.end.push_back(turned(from + any_point(0.1), any_axis(), angle)).ignore();
  }
  return d;
}

// The plan of `d` on the rest positions of `m`, moved to its end.
bool build(math::WarpPlan& plan, const mesh::Mesh& m, const StrokeDraw& d) {
  const math::ConstVertexColumns rest(m.x(), m.y(), m.z());
  if (!plan.build(rest, d.start, d.radius, math::WarpMethod::twister).ok()) return false;
  return plan.update(d.end).ok();
}

// Is any edge over the threshold (under `warp`, at the start) outside the region?
bool offending_edge_outside(const mesh::Mesh& m, const mesh::PointWarp& warp, double threshold,
                            const math::WarpPlan& plan) {
  std::vector<bool> in(m.vertex_count(), false);
  for (const std::uint32_t v : plan.indices()) in[v] = true;
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    const auto tv = m.triangle(t);
    if (in[tv[0]] || in[tv[1]] || in[tv[2]]) continue;
    for (int i = 0; i < 3; ++i) {
      const glm::dvec3 a(m.position(tv[i]));
      const glm::dvec3 b(m.position(tv[(i + 1) % 3]));
      if (mesh::MeshRefiner::midpoint_error(a, b, warp) > threshold) return true;
    }
  }
  return false;
}

// The commit's placement: the plan's vertices and the new ones where S takes them.
void place(mesh::Mesh& m, const math::WarpPlan& plan, const mesh::MeshRefiner& refiner,
           std::uint32_t vertices_before) {
  for (const std::uint32_t v : plan.indices()) {
    m.set_position(v, glm::vec3(plan.warp_point(glm::dvec3(m.position(v)))));
  }
  for (std::uint32_t v = vertices_before; v < m.vertex_count(); ++v) {
    m.set_position(v, glm::vec3(refiner.warped(v)));
  }
}

RC_GTEST_PROP(RefineLocal,
              SameSplitsAndBitsAsTheWholeMeshRefinerWhenTheRegionHoldsEveryOffendingEdge, ()) {
  const auto spare = static_cast<std::size_t>(*rc::gen::inRange(0, 6000));
  auto whole = any_mesh(spare);
  auto local = std::make_unique<meshio::MeshBuffer>(whole->mesh().vertex_capacity(),
                                                    whole->mesh().triangle_capacity());
  RC_ASSERT(local->mesh().copy_from(whole->mesh()).ok());
  const bool manifold_start = edge_incidence(whole->mesh()).nonmanifold == 0;
  meshio::RefinerBuffer whole_refiner(whole->mesh().vertex_capacity(),
                                      whole->mesh().triangle_capacity());
  meshio::RefinerBuffer local_refiner(whole->mesh().vertex_capacity(),
                                      whole->mesh().triangle_capacity());
  mesh::MeshRefiner global(whole_refiner.storage());
  mesh::MeshRefiner around(local_refiner.storage());
  math::WarpPlanWithStorage<40'000> plan_global;
  math::WarpPlanWithStorage<40'000> plan_local;
  const int strokes = *rc::gen::inRange(1, 4);
  bool identical = true;  // so far every stroke met the condition
  for (int k = 0; k < strokes; ++k) {
    const double threshold = *rc::gen::inRange(2, 60) * 1e-4;
    // The same plan on both meshes (same rest positions while identical).
    const StrokeDraw draw = any_stroke();
    const bool built_global = build(plan_global, whole->mesh(), draw);
    const bool built_local = build(plan_local, local->mesh(), draw);
    RC_ASSERT(built_global == built_local);
    if (!built_global) continue;
    const PlanWarp warp_global(plan_global);
    const PlanWarp warp_local(plan_local);
    const bool outside = offending_edge_outside(local->mesh(), warp_local, threshold, plan_local);
    const auto vg = static_cast<std::uint32_t>(whole->mesh().vertex_count());
    const auto vl = static_cast<std::uint32_t>(local->mesh().vertex_count());
    const auto rg = global.refine(whole->mesh(), warp_global, threshold);
    // Half the time with the plan's own float images of its vertices (as a commit
    // passes its live columns), else the refiner warps them itself.
    const bool with_images = *rc::gen::arbitrary<bool>();
    const mesh::Mesh& lm = local->mesh();
    std::vector<float> ix(lm.x().begin(), lm.x().end());
    std::vector<float> iy(lm.y().begin(), lm.y().end());
    std::vector<float> iz(lm.z().begin(), lm.z().end());
    RC_ASSERT(plan_local
                  .apply(math::ConstVertexColumns(lm.x(), lm.y(), lm.z()),
                         math::VertexColumns(ix, iy, iz))
                  .ok());
    const mesh::VertexImages images =
        with_images ? mesh::VertexImages{ix, iy, iz} : mesh::VertexImages{};
    RC_CLASSIFY(with_images, "the plan's images given");
    const auto rl = around.refine_around(local->mesh(), warp_local, threshold, plan_local.indices(),
                                         nullptr, images);
    RC_ASSERT(rg.ok());
    RC_ASSERT(rl.ok());
    // Conforming and, where it ran to the end, every region edge within the threshold.
    const auto inc = edge_incidence(local->mesh());
    if (manifold_start) {
      RC_ASSERT(inc.nonmanifold == 0);
      RC_ASSERT(inc.degenerate == 0);
    }
    identical = identical && !outside;
    RC_CLASSIFY(outside, "an offending edge outside the region");
    RC_CLASSIFY(rl->edges_split > 0, "splits");
    RC_CLASSIFY(rl->stop != mesh::RefineStop::done, "capacity stop");
    RC_CLASSIFY(around.settled_in_float() > 0, "edges settled in float");
    if (identical) {
      RC_ASSERT(rl->edges_split == rg->edges_split);
      RC_ASSERT(rl->triangles_added == rg->triangles_added);
      RC_ASSERT(rl->triangles_changed == rg->triangles_changed);
      RC_ASSERT(rl->stop == rg->stop);
      RC_ASSERT(rl->blocked == rg->blocked);
      RC_ASSERT(local->mesh().checksum() == whole->mesh().checksum());
      for (std::uint32_t v = vl; v < local->mesh().vertex_count(); ++v) {
        const glm::dvec3 a = around.warped(v);
        const glm::dvec3 b = global.warped(v);
        RC_ASSERT(a.x == b.x && a.y == b.y && a.z == b.z);
      }
    }
    place(whole->mesh(), plan_global, global, vg);
    place(local->mesh(), plan_local, around, vl);
    if (!identical) break;  // different meshes from here on: nothing more to compare
  }
}

// The float filter's premise: warp_points_float stays within float_error_bound of
// warp_point, for points (and float midpoints) anywhere near random one- and two-hand
// strokes (turns up to 170 degrees and the long way round, squash, drags); and the bound
// is mostly well under 0.1 mm (close grabs, whose squash steepens the weight, and turns
// the long way round give larger bounds: there the filter settles fewer edges).
RC_GTEST_PROP(RefineFloat, TheFloatWarpIsWithinItsBoundOfTheDoubleWarp, ()) {
  meshio::MeshBuffer grid(meshio::grid_vertices(2), meshio::grid_triangles(2));
  RC_ASSERT(meshio::make_grid(grid.mesh(), 2, 0.3f).ok());
  math::WarpPlanWithStorage<16> plan;
  const StrokeDraw draw = any_stroke();
  RC_PRE(build(plan, grid.mesh(), draw));
  if (*rc::gen::inRange(0, 3) == 0) {  // the long way round
    RC_PRE(plan.update_turns(draw.end, static_cast<std::uint8_t>(*rc::gen::inRange(1, 4))).ok());
  }
  constexpr std::size_t n = math::WarpPlan::kFloatChunk;
  std::array<float, n> x{}, y{}, z{}, ox{}, oy{}, oz{};
  const glm::dvec3 around_grab = draw.start[0].origin;
  float extent = 0.0f;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 p = around_grab + any_point(draw.radius * 1.2);
    x[i] = static_cast<float>(p.x);
    y[i] = static_cast<float>(p.y);
    z[i] = static_cast<float>(p.z);
    extent = std::max({extent, std::abs(x[i]), std::abs(y[i]), std::abs(z[i])});
  }
  RC_ASSERT(
      plan.warp_points_float(x.data(), y.data(), z.data(), ox.data(), oy.data(), oz.data(), n));
  const double bound = plan.float_error_bound(extent);
  RC_TAG(bound < 1e-4 ? "bound < 0.1 mm" : "bound >= 0.1 mm (the float filter settles less)");
  double worst = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 d = plan.warp_point(glm::dvec3(x[i], y[i], z[i]));
    worst = std::max(worst, glm::length(glm::dvec3(ox[i], oy[i], oz[i]) - d));
  }
  RC_ASSERT(worst <= bound);
  RC_TAG(worst <= bound / 8 ? "margin >= 8x" : "margin < 8x");
}

// A mesh with an edge on three triangles: refine_around refines it like refine().
TEST(RefineLocal, ANonManifoldMeshIsRefinedAsAWhole) {
  meshio::MeshBuffer a(5 + 200, 3 + 400);
  mesh::Mesh& m = a.mesh();
  for (const glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(0.2f, 0, 0), glm::vec3(0.1f, 0.2f, 0),
                            glm::vec3(0.1f, -0.2f, 0), glm::vec3(0.1f, 0, 0.2f)}) {
    ASSERT_TRUE(m.add_vertex(p).ok());
  }
  ASSERT_TRUE(m.add_triangle(0, 1, 2).ok());
  ASSERT_TRUE(m.add_triangle(1, 0, 3).ok());
  ASSERT_TRUE(m.add_triangle(0, 1, 4).ok());
  meshio::MeshBuffer b(m.vertex_capacity(), m.triangle_capacity());
  ASSERT_TRUE(b.mesh().copy_from(m).ok());
  math::WarpPlanWithStorage<1000> plan;
  const math::ConstVertexColumns rest(m.x(), m.y(), m.z());
  const std::array<math::Frame, 1> start{math::identity_frame({0.1, 0.0, 0.0})};
  const std::array<math::Frame, 1> end{turned({0.1, 0.0, 0.05}, {1, 0, 0}, 2.0)};
  ASSERT_TRUE(plan.build(rest, start, 0.3, math::WarpMethod::twister).ok());
  ASSERT_TRUE(plan.update(end).ok());
  const PlanWarp warp(plan);
  meshio::RefinerBuffer ra(m.vertex_capacity(), m.triangle_capacity());
  meshio::RefinerBuffer rb(m.vertex_capacity(), m.triangle_capacity());
  mesh::MeshRefiner global(ra.storage());
  mesh::MeshRefiner around(rb.storage());
  const auto rg = global.refine(m, warp, 0.001);
  const auto rl = around.refine_around(b.mesh(), warp, 0.001, plan.indices());
  ASSERT_TRUE(rg.ok() && rl.ok());
  EXPECT_GT(rl->edges_split, 0u);
  EXPECT_EQ(rl->blocked, rg->blocked);
  EXPECT_EQ(b.mesh().checksum(), m.checksum());
}

// The adjacency is rebuilt when the topology changed behind the refiner's back (an
// undo of a refined commit shrinks and rewrites the mesh), and reused otherwise.
// A 0.3 m sphere with room for 4,000 more vertices, and a one-hand 2.5 rad twist
// of its top (radius 0.25 m).
struct TwistedSphere {
  static constexpr std::size_t kSpare = 4000;
  TwistedSphere() {
    EXPECT_TRUE(meshio::make_sphere(buffer.mesh(), 12, 24, 0.3f).ok());
    const mesh::Mesh& m = buffer.mesh();
    const std::array<math::Frame, 1> start{math::identity_frame({0.0, 0.0, 0.3})};
    const std::array<math::Frame, 1> end{turned({0.0, 0.0, 0.35}, {0, 0, 1}, 2.5)};
    EXPECT_TRUE(plan.build({m.x(), m.y(), m.z()}, start, 0.25, math::WarpMethod::twister).ok());
    EXPECT_TRUE(plan.update(end).ok());
  }
  meshio::MeshBuffer buffer{meshio::sphere_vertices(12, 24) + kSpare,
                            meshio::sphere_triangles(12, 24) + 2 * kSpare};
  math::WarpPlanWithStorage<kSpare> plan;
};

TEST(RefineLocal, AChangedTopologyIsSeenAndTheResultStaysTheWholeMeshOne) {
  TwistedSphere s;
  meshio::MeshBuffer& a = s.buffer;
  math::WarpPlan& plan = s.plan;
  meshio::MeshBuffer b(a.mesh().vertex_capacity(), a.mesh().triangle_capacity());
  ASSERT_TRUE(b.mesh().copy_from(a.mesh()).ok());
  const std::size_t v0 = a.mesh().vertex_count();
  const std::size_t t0 = a.mesh().triangle_count();
  std::vector<std::array<std::uint32_t, 3>> before;
  for (std::uint32_t t = 0; t < t0; ++t) before.push_back(a.mesh().triangle(t));
  const PlanWarp warp(plan);
  meshio::RefinerBuffer ra(a.mesh().vertex_capacity(), a.mesh().triangle_capacity());
  meshio::RefinerBuffer rb(a.mesh().vertex_capacity(), a.mesh().triangle_capacity());
  mesh::MeshRefiner global(ra.storage());
  mesh::MeshRefiner around(rb.storage());
  for (int round = 0; round < 3; ++round) {
    const auto rg = global.refine(a.mesh(), warp, 0.0005);
    const auto rl = around.refine_around(b.mesh(), warp, 0.0005, plan.indices());
    ASSERT_TRUE(rg.ok() && rl.ok());
    EXPECT_GT(rl->edges_split, 0u);
    EXPECT_EQ(b.mesh().checksum(), a.mesh().checksum()) << round;
    // Undo: back to the start topology.
    for (auto* m : {&a.mesh(), &b.mesh()}) {
      ASSERT_TRUE(m->resize(v0, t0).ok());
      for (std::uint32_t t = 0; t < t0; ++t) m->set_triangle(t, before[t]);
    }
  }
}

TEST(RefineLocal, AllocatesNothing) {
  TwistedSphere s;
  meshio::MeshBuffer& a = s.buffer;
  const PlanWarp warp(s.plan);
  meshio::RefinerBuffer rb(a.mesh().vertex_capacity(), a.mesh().triangle_capacity());
  mesh::MeshRefiner around(rb.storage());
  Result<mesh::RefineResult> rl = StatusCode::unavailable;
  EXPECT_NO_ALLOCATIONS(rl = around.refine_around(a.mesh(), warp, 0.0005, s.plan.indices()));
  ASSERT_TRUE(rl.ok());
  EXPECT_GT(rl->edges_split, 0u);
}

// The pass without bookkeeping (nothing over the threshold, images given) finds each
// region edge exactly once on any mesh: closed or open, consistently wound or not.
RC_GTEST_PROP(RefineLocal, NothingToSplitSettlesEachRegionEdgeOnce, ()) {
  auto b = any_mesh(6000);
  mesh::Mesh& m = b->mesh();
  math::WarpPlanWithStorage<40'000> plan;
  RC_PRE(build(plan, m, any_stroke()));
  std::vector<float> ix(m.x().begin(), m.x().end());
  std::vector<float> iy(m.y().begin(), m.y().end());
  std::vector<float> iz(m.z().begin(), m.z().end());
  RC_ASSERT(
      plan.apply(math::ConstVertexColumns(m.x(), m.y(), m.z()), math::VertexColumns(ix, iy, iz))
          .ok());
  const std::uint64_t before = m.checksum();
  const PlanWarp warp(plan);
  meshio::RefinerBuffer rb(m.vertex_capacity(), m.triangle_capacity());
  mesh::MeshRefiner around(rb.storage());
  const auto rl = around.refine_around(m, warp, 10.0, plan.indices(), nullptr, {ix, iy, iz});
  RC_ASSERT(rl.ok());
  RC_ASSERT(rl->edges_split == 0u);
  RC_ASSERT(m.checksum() == before);
  std::vector<bool> in(m.vertex_count(), false);
  for (const std::uint32_t v : plan.indices()) in[v] = true;
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    const auto tv = m.triangle(t);
    if (!in[tv[0]] && !in[tv[1]] && !in[tv[2]]) continue;
    for (int i = 0; i < 3; ++i) edges.insert(std::minmax(tv[i], tv[(i + 1) % 3]));
  }
  RC_ASSERT(around.settled_in_float() == edges.size());
  // At a threshold some strokes exceed: when nothing splits, no region edge was over.
  const double threshold = *rc::gen::inRange(2, 60) * 1e-4;
  const auto tight =
      around.refine_around(m, warp, threshold, plan.indices(), nullptr, {ix, iy, iz});
  RC_ASSERT(tight.ok());
  const bool none = tight->edges_split == 0u && tight->stop == mesh::RefineStop::done;
  RC_CLASSIFY(none, "nothing split at the tight threshold");
  if (!none) return;
  for (const auto& [a, c] : edges) {
    const double e = mesh::MeshRefiner::midpoint_error(glm::dvec3(m.position(a)),
                                                       glm::dvec3(m.position(c)), warp);
    RC_ASSERT(e <= threshold);
  }
}

// A commit's case: the plan's images given and nothing over the threshold. Every
// region edge is settled in float (no double warp, no visit in index order), in one
// walk that allocates nothing, and the mesh is left as it was.
TEST(RefineLocal, WithTheStrokesImagesEveryEdgeWithinIsSettledInFloatAlone) {
  TwistedSphere s;
  mesh::Mesh& m = s.buffer.mesh();
  const std::uint64_t before = m.checksum();
  std::vector<float> ix(m.x().begin(), m.x().end());
  std::vector<float> iy(m.y().begin(), m.y().end());
  std::vector<float> iz(m.z().begin(), m.z().end());
  ASSERT_TRUE(
      s.plan.apply(math::ConstVertexColumns(m.x(), m.y(), m.z()), math::VertexColumns(ix, iy, iz))
          .ok());
  const PlanWarp warp(s.plan);
  meshio::RefinerBuffer rb(m.vertex_capacity(), m.triangle_capacity());
  mesh::MeshRefiner around(rb.storage());
  Result<mesh::RefineResult> rl = StatusCode::unavailable;
  EXPECT_NO_ALLOCATIONS(
      rl = around.refine_around(m, warp, 0.05, s.plan.indices(), nullptr, {ix, iy, iz}));
  ASSERT_TRUE(rl.ok());
  EXPECT_EQ(rl->edges_split, 0u);
  EXPECT_EQ(m.checksum(), before);
  // Every edge of a triangle with a plan vertex, once.
  std::vector<bool> in(m.vertex_count(), false);
  for (const std::uint32_t v : s.plan.indices()) in[v] = true;
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    const auto tv = m.triangle(t);
    if (!in[tv[0]] && !in[tv[1]] && !in[tv[2]]) continue;
    for (int i = 0; i < 3; ++i) {
      edges.insert(std::minmax(tv[i], tv[(i + 1) % 3]));
    }
  }
  EXPECT_EQ(around.settled_in_float(), edges.size());
}

}  // namespace
}  // namespace twister::session
