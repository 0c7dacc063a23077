// Vertex normals: outward on a closed box (a corner's is the mean of its faces'),
// unit everywhere, zero where no triangle has area; no allocation.
#include "twister/mesh/vertex_normals.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <glm/geometric.hpp>

#include "allocation_counter.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace twister::mesh {
namespace {

TEST(VertexNormals, PointOutOfABox) {
  meshio::MeshBuffer b(meshio::box_vertices(4), meshio::box_triangles(4));
  ASSERT_TRUE(meshio::make_box(b.mesh(), 4, 0.5f).ok());
  std::array<float, 64> x{}, y{}, z{};
  ASSERT_TRUE(compute_vertex_normals(b.mesh(), {x, y, z}).ok());
  for (std::uint32_t v = 0; v < b.mesh().vertex_count(); ++v) {
    const glm::vec3 n(x[v], y[v], z[v]);
    const glm::vec3 p = b.mesh().position(v);
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
    EXPECT_GT(glm::dot(n, p), 0.0f) << "vertex " << v;
    // The middle of a face: that face's normal exactly.
    if (std::abs(p.z) == 0.5f && std::abs(p.x) < 0.5f && std::abs(p.y) < 0.5f) {
      EXPECT_EQ(n, glm::vec3(0, 0, p.z > 0 ? 1 : -1));
    }
  }
}

TEST(VertexNormals, ZeroWithoutAreaAndShortColumnsRefused) {
  MeshWithStorage<4, 2> m;
  (void)m.add_vertex({0, 0, 0});
  (void)m.add_vertex({1, 0, 0});
  (void)m.add_vertex({2, 0, 0});
  (void)m.add_vertex({0, 1, 0});
  (void)m.add_triangle(0, 1, 2);  // no area: a line
  std::array<float, 4> x{}, y{}, z{};
  x.fill(9.0f);
  ASSERT_TRUE(compute_vertex_normals(m, {x, y, z}).ok());
  for (int v = 0; v < 4; ++v) EXPECT_EQ(glm::vec3(x[v], y[v], z[v]), glm::vec3(0.0f));
  EXPECT_EQ(compute_vertex_normals(m, {std::span(x).first(3), y, z}).code(),
            StatusCode::invalid_argument);
}

TEST(VertexNormals, DoNotAllocate) {
  static meshio::MeshBuffer b(meshio::sphere_vertices(40, 80), meshio::sphere_triangles(40, 80));
  ASSERT_TRUE(meshio::make_sphere(b.mesh(), 40, 80, 1.0f).ok());
  static std::array<float, meshio::sphere_vertices(40, 80)> x{}, y{}, z{};
  EXPECT_NO_ALLOCATIONS({ compute_vertex_normals(b.mesh(), {x, y, z}).ignore(); });
}

}  // namespace
}  // namespace twister::mesh
