// The procedural meshes `twister mesh` writes: closed ones (box, cylinder, sphere)
// are conforming manifolds oriented outward (positive volume), exactly their counts.
#include "twister/meshio/mesh_generator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "mesh_checks.hpp"
#include "twister/meshio/mesh_buffer.hpp"

namespace twister::meshio {
namespace {

using test_support::closed_manifold;
using test_support::edge_incidence;

// Signed volume (divergence theorem): positive when every triangle faces outward.
double volume(const mesh::Mesh& m) {
  double v = 0.0;
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    const auto i = m.triangle(t);
    const glm::dvec3 a(m.position(i[0])), b(m.position(i[1])), c(m.position(i[2]));
    v += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return v;
}

TEST(MeshGenerator, BoxIsAClosedOutwardManifold) {
  for (const std::size_t n : {2u, 3u, 5u, 12u}) {
    MeshBuffer b(box_vertices(n), box_triangles(n));
    ASSERT_TRUE(make_box(b.mesh(), n, 0.5f).ok());
    EXPECT_EQ(b.mesh().vertex_count(), box_vertices(n));
    EXPECT_EQ(b.mesh().triangle_count(), box_triangles(n));
    EXPECT_TRUE(closed_manifold(b.mesh())) << n;
    EXPECT_NEAR(volume(b.mesh()), 1.0, 1e-6) << n;
    for (std::uint32_t i = 0; i < b.mesh().vertex_count(); ++i) {
      const glm::vec3 p = b.mesh().position(i);
      const float m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
      EXPECT_EQ(m, 0.5f) << "vertex " << i << " is not on the box";
    }
  }
}

TEST(MeshGenerator, CylinderIsAClosedOutwardManifold) {
  MeshBuffer c(cylinder_vertices(6, 24), cylinder_triangles(6, 24));
  ASSERT_TRUE(make_cylinder(c.mesh(), 6, 24, 0.25f, 0.5f).ok());
  EXPECT_EQ(c.mesh().vertex_count(), cylinder_vertices(6, 24));
  EXPECT_TRUE(closed_manifold(c.mesh()));
  const double prism = 0.5 * 24 * 0.25 * 0.25 * std::sin(2 * std::numbers::pi / 24) * 1.0;
  EXPECT_NEAR(volume(c.mesh()), prism, 1e-6);
}

TEST(MeshGenerator, SphereIsAClosedOutwardManifoldAndThePlaneAnOpenOne) {
  MeshBuffer s(sphere_vertices(10, 16), sphere_triangles(10, 16));
  ASSERT_TRUE(make_sphere(s.mesh(), 10, 16, 1.0f).ok());
  EXPECT_TRUE(closed_manifold(s.mesh()));
  EXPECT_GT(volume(s.mesh()), 3.5);
  MeshBuffer g(grid_vertices(5), grid_triangles(5));
  ASSERT_TRUE(make_grid(g.mesh(), 5, 1.0f).ok());
  const auto e = edge_incidence(g.mesh());
  EXPECT_EQ(e.boundary, 16u);
  EXPECT_EQ(e.nonmanifold + e.same_direction + e.degenerate, 0u);
}

TEST(MeshGenerator, RefusesWhatItCannotMake) {
  MeshBuffer small(8, 12);
  EXPECT_EQ(make_box(small.mesh(), 1, 1.0f).code(), StatusCode::invalid_argument);
  EXPECT_EQ(make_box(small.mesh(), 3, 1.0f).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(make_box(small.mesh(), 2, std::nanf("")).code(), StatusCode::invalid_argument);
  ASSERT_TRUE(make_box(small.mesh(), 2, 1.0f).ok());
  EXPECT_EQ(make_cylinder(small.mesh(), 0, 8, 1.0f, 1.0f).code(), StatusCode::invalid_argument);
  EXPECT_EQ(make_cylinder(small.mesh(), 1, 2, 1.0f, 1.0f).code(), StatusCode::invalid_argument);
  EXPECT_EQ(make_cylinder(small.mesh(), 4, 8, 1.0f, 1.0f).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(small.mesh().vertex_count(), 0u);
}

}  // namespace
}  // namespace twister::meshio
