// The closed/manifold counts of check_mesh() on small meshes we can count by hand,
// and as properties (rapidcheck) of generated meshes with triangles removed.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <set>
#include <vector>

#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_export.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace twister::meshio {
namespace {

// A copy of `from` without the triangles in `drop`.
void copy_without(const mesh::Mesh& from, const std::set<std::uint32_t>& drop, mesh::Mesh& to) {
  to.clear();
  for (std::uint32_t i = 0; i < from.vertex_count(); ++i) (void)to.add_vertex(from.position(i));
  for (std::uint32_t t = 0; t < from.triangle_count(); ++t) {
    if (drop.count(t) != 0) continue;
    const auto v = from.triangle(t);
    (void)to.add_triangle(v[0], v[1], v[2]);
  }
}

TEST(MeshCheck, ClosedBoxIsWatertight) {
  MeshBuffer box(box_vertices(4), box_triangles(4));
  ASSERT_TRUE(make_box(box.mesh(), 4, 0.1F).ok());
  const MeshCheck c = check_mesh(box.mesh());
  EXPECT_TRUE(c.watertight()) << describe(c);
  EXPECT_EQ(c.open_edges, 0U);
  EXPECT_EQ(c.non_manifold_edges, 0U);
  EXPECT_EQ(c.misoriented_edges, 0U);
  EXPECT_TRUE(c.intersections_checked);
  EXPECT_EQ(c.self_intersections, 0U);
  // Euler: a closed triangle mesh has E = 3T / 2.
  EXPECT_EQ(c.edges, 3 * c.triangles / 2);
}

TEST(MeshCheck, BoxWithAFaceRemovedHasItsRimOpen) {
  const std::size_t n = 4;
  MeshBuffer box(box_vertices(n), box_triangles(n));
  ASSERT_TRUE(make_box(box.mesh(), n, 0.1F).ok());
  // The box's first face: the first 2 (n-1)^2 triangles, a square grid with a rim of
  // 4 (n-1) edges.
  std::set<std::uint32_t> face;
  for (std::uint32_t t = 0; t < 2 * (n - 1) * (n - 1); ++t) face.insert(t);
  MeshBuffer open(box_vertices(n), box_triangles(n));
  copy_without(box.mesh(), face, open.mesh());
  const MeshCheck c = check_mesh(open.mesh());
  EXPECT_FALSE(c.closed());
  EXPECT_TRUE(c.manifold());
  EXPECT_EQ(c.open_edges, 4 * (n - 1)) << describe(c);
  EXPECT_NE(describe(c).find("12 open edges"), std::string::npos) << describe(c);
}

TEST(MeshCheck, HandCountedCases) {
  MeshBuffer m(8, 8);
  for (const glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0),
                            glm::vec3(0, -1, 0), glm::vec3(0, 0, 1)}) {
    (void)m.mesh().add_vertex(p);
  }
  ASSERT_TRUE(m.mesh().add_triangle(0, 1, 2).ok());
  MeshCheck c = check_mesh(m.mesh());
  EXPECT_EQ(c.open_edges, 3U);
  EXPECT_EQ(c.edges, 3U);
  // A second triangle on edge 0-1 running it the other way: consistent.
  ASSERT_TRUE(m.mesh().add_triangle(1, 0, 3).ok());
  c = check_mesh(m.mesh());
  EXPECT_EQ(c.open_edges, 4U);
  EXPECT_EQ(c.misoriented_edges, 0U);
  // A third on the same edge: non-manifold (a fin).
  ASSERT_TRUE(m.mesh().add_triangle(0, 1, 4).ok());
  c = check_mesh(m.mesh());
  EXPECT_EQ(c.non_manifold_edges, 1U);
  EXPECT_FALSE(c.manifold());
  // Two triangles running a shared edge the same way: misoriented.
  MeshBuffer flip(4, 2);
  for (const glm::vec3 p :
       {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0)}) {
    (void)flip.mesh().add_vertex(p);
  }
  ASSERT_TRUE(flip.mesh().add_triangle(0, 1, 2).ok());
  ASSERT_TRUE(flip.mesh().add_triangle(0, 1, 3).ok());
  c = check_mesh(flip.mesh());
  EXPECT_EQ(c.misoriented_edges, 1U);
  EXPECT_FALSE(c.manifold());
  // A repeated vertex is a degenerate triangle.
  ASSERT_TRUE(m.mesh().add_triangle(2, 2, 4).ok());
  EXPECT_EQ(check_mesh(m.mesh()).degenerate_triangles, 1U);
}

TEST(MeshCheck, CrossingTrianglesAreCounted) {
  MeshBuffer m(6, 2);
  // Two triangles sharing no vertex, piercing each other like links of a chain.
  for (const glm::vec3 p : {glm::vec3(-1, 0, -1), glm::vec3(1, 0, -1), glm::vec3(0, 0, 1),
                            glm::vec3(0, -1, 0), glm::vec3(0, 1, 0.2F), glm::vec3(0, 1, -0.2F)}) {
    (void)m.mesh().add_vertex(p);
  }
  ASSERT_TRUE(m.mesh().add_triangle(0, 1, 2).ok());
  ASSERT_TRUE(m.mesh().add_triangle(3, 4, 5).ok());
  EXPECT_EQ(check_mesh(m.mesh()).self_intersections, 1U);
  // Moved apart: none.
  for (std::uint32_t v = 3; v < 6; ++v)
    m.mesh().set_position(v, m.mesh().position(v) + glm::vec3(5, 0, 0));
  EXPECT_EQ(check_mesh(m.mesh()).self_intersections, 0U);
}

TEST(MeshCheck, TwoOverlappingBoxesIntersectAndASphereDoesNot) {
  const std::size_t n = 3;
  MeshBuffer two(2 * box_vertices(n), 2 * box_triangles(n));
  MeshBuffer box(box_vertices(n), box_triangles(n));
  ASSERT_TRUE(make_box(box.mesh(), n, 0.1F).ok());
  for (int copy = 0; copy < 2; ++copy) {
    const auto base = static_cast<std::uint32_t>(two.mesh().vertex_count());
    for (std::uint32_t i = 0; i < box.mesh().vertex_count(); ++i) {
      (void)two.mesh().add_vertex(box.mesh().position(i) +
                                  glm::vec3(0.07F * copy, 0.03F * copy, 0.05F * copy));
    }
    for (std::uint32_t t = 0; t < box.mesh().triangle_count(); ++t) {
      const auto v = box.mesh().triangle(t);
      (void)two.mesh().add_triangle(base + v[0], base + v[1], base + v[2]);
    }
  }
  const MeshCheck c = check_mesh(two.mesh());
  EXPECT_TRUE(c.closed());
  EXPECT_GT(c.self_intersections, 0U) << describe(c);
  MeshBuffer sphere(sphere_vertices(24, 32), sphere_triangles(24, 32));
  ASSERT_TRUE(make_sphere(sphere.mesh(), 24, 32, 0.2F).ok());
  EXPECT_EQ(check_mesh(sphere.mesh()).self_intersections, 0U);
  EXPECT_TRUE(check_mesh(sphere.mesh()).watertight());
  // Too many triangles for the grid count: skipped, and said so.
  const MeshCheck skipped =
      check_mesh(sphere.mesh(), {.intersections = true, .max_intersection_triangles = 10});
  EXPECT_FALSE(skipped.intersections_checked);
  EXPECT_NE(describe(skipped).find("not checked"), std::string::npos);
}

// Removing k triangles no two of which share an edge from a closed manifold mesh
// opens exactly 3k edges and leaves it manifold.
RC_GTEST_PROP(MeshCheckProperty, RemovedTrianglesOpenThreeEdgesEach, ()) {
  const auto rings = *rc::gen::inRange<std::size_t>(3, 12);
  const auto segments = *rc::gen::inRange<std::size_t>(3, 16);
  MeshBuffer sphere(sphere_vertices(rings, segments), sphere_triangles(rings, segments));
  RC_ASSERT(make_sphere(sphere.mesh(), rings, segments, 0.3F).ok());
  const auto picks =
      *rc::gen::container<std::vector<std::uint32_t>>(rc::gen::inRange<std::uint32_t>(
          0, static_cast<std::uint32_t>(sphere.mesh().triangle_count())));
  // Keep the picks that share no vertex with an earlier pick (so no shared edge).
  std::set<std::uint32_t> drop;
  std::set<std::uint32_t> used;
  for (const std::uint32_t t : picks) {
    const auto v = sphere.mesh().triangle(t);
    if (used.count(v[0]) + used.count(v[1]) + used.count(v[2]) != 0) continue;
    drop.insert(t);
    used.insert(v.begin(), v.end());
  }
  MeshBuffer open(sphere_vertices(rings, segments), sphere_triangles(rings, segments));
  copy_without(sphere.mesh(), drop, open.mesh());
  const MeshCheck c = check_mesh(open.mesh(), {.intersections = false});
  RC_ASSERT(c.open_edges == 3 * drop.size());
  RC_ASSERT(c.manifold());
  RC_ASSERT(c.closed() == drop.empty());
}

// An n x n grid: its rim is open (4 (n-1) edges), its inside manifold.
RC_GTEST_PROP(MeshCheckProperty, GridRimIsOpen, ()) {
  const auto n = *rc::gen::inRange<std::size_t>(2, 20);
  MeshBuffer grid(grid_vertices(n), grid_triangles(n));
  RC_ASSERT(make_grid(grid.mesh(), n, 0.5F).ok());
  const MeshCheck c = check_mesh(grid.mesh());
  RC_ASSERT(c.open_edges == 4 * (n - 1));
  RC_ASSERT(c.manifold());
  RC_ASSERT(c.self_intersections == 0U);
}

}  // namespace
}  // namespace twister::meshio
