#include "twister/mesh/mesh.hpp"

#include <gtest/gtest.h>

#include "allocation_counter.hpp"

namespace twister::mesh {
namespace {

TEST(Mesh, AddsVerticesAndTrianglesUpToCapacity) {
  MeshWithStorage<3, 1> m;
  EXPECT_EQ(m.vertex_capacity(), 3u);
  EXPECT_EQ(m.triangle_capacity(), 1u);
  ASSERT_EQ(*m.add_vertex({0, 0, 0}), 0u);
  ASSERT_EQ(*m.add_vertex({1, 0, 0}), 1u);
  EXPECT_EQ(m.add_triangle(0, 1, 2).status().code(), StatusCode::invalid_argument);
  ASSERT_EQ(*m.add_vertex({0, 1, 0}), 2u);
  EXPECT_EQ(m.add_vertex({9, 9, 9}).status().code(), StatusCode::resource_exhausted);
  ASSERT_TRUE(m.add_triangle(0, 1, 2).ok());
  EXPECT_EQ(m.add_triangle(0, 1, 2).status().code(), StatusCode::resource_exhausted);
  EXPECT_EQ(m.vertex_count(), 3u);
  EXPECT_EQ(m.triangle_count(), 1u);
  EXPECT_EQ(m.x().size(), 3u);
  EXPECT_EQ(m.position(1), glm::vec3(1, 0, 0));
  EXPECT_EQ(m.triangle_indices()[2], 2u);
}

TEST(Mesh, ChecksumSeesEveryBit) {
  MeshWithStorage<4, 2> a;
  MeshWithStorage<8, 4> b;
  for (Mesh* m : {static_cast<Mesh*>(&a), static_cast<Mesh*>(&b)}) {
    (void)m->add_vertex({0, 0, 0});
    (void)m->add_vertex({1, 0, 0});
    (void)m->add_vertex({0, 1, 0});
    (void)m->add_triangle(0, 1, 2);
  }
  EXPECT_EQ(a.checksum(), b.checksum());
  b.set_position(1, {1.0f, 0.0f, -0.0f});  // only the sign bit differs
  EXPECT_NE(a.checksum(), b.checksum());
  ASSERT_TRUE(b.copy_from(a).ok());
  EXPECT_EQ(a.checksum(), b.checksum());
  (void)b.add_vertex({0, 0, 1});
  EXPECT_NE(a.checksum(), b.checksum());
  EXPECT_EQ(a.copy_from(b).code(), StatusCode::ok);
  MeshWithStorage<2, 1> small;
  EXPECT_EQ(small.copy_from(a).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(small.vertex_count(), 0u);
}

TEST(Mesh, TrianglesRewriteAndCountsResize) {
  MeshWithStorage<4, 2> m;
  for (int i = 0; i < 3; ++i) (void)m.add_vertex({float(i), 0, 0});
  (void)m.add_triangle(0, 1, 2);
  m.set_triangle(0, {2, 0, 1});
  EXPECT_EQ(m.triangle(0), (std::array<std::uint32_t, 3>{2, 0, 1}));
  ASSERT_TRUE(m.resize(2, 0).ok());
  EXPECT_EQ(m.vertex_count(), 2u);
  EXPECT_EQ(m.triangle_count(), 0u);
  ASSERT_TRUE(m.resize(3, 1).ok());  // the storage still holds what was there
  EXPECT_EQ(m.triangle(0), (std::array<std::uint32_t, 3>{2, 0, 1}));
  EXPECT_EQ(m.position(2), glm::vec3(2, 0, 0));
  EXPECT_EQ(m.resize(5, 1).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(m.resize(3, 3).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(m.vertex_count(), 3u);
}

TEST(Mesh, NoAllocation) {
  static MeshWithStorage<1000, 1000> m;
  EXPECT_NO_ALLOCATIONS({
    for (int i = 0; i < 1000; ++i) (void)m.add_vertex({float(i), 0, 0});
    (void)m.checksum();
  });
}

}  // namespace
}  // namespace twister::mesh
