#include "twister/session/live_mesh.hpp"

#include <gtest/gtest.h>

#include <array>

#include "twister/mesh/mesh.hpp"

namespace twister::session {
namespace {

TEST(LiveMesh, ViewsAreSizedToTheMeshVertexCount) {
  mesh::MeshWithStorage<8, 8> m;
  std::array<float, 8> x{}, y{}, z{};
  LiveMesh live(m, x, y, z);
  EXPECT_EQ(live.rest().size(), 0u);
  EXPECT_EQ(live.live().size(), 0u);
  ASSERT_TRUE(m.add_vertex({1, 2, 3}).ok());
  ASSERT_TRUE(m.add_vertex({4, 5, 6}).ok());
  EXPECT_EQ(live.rest().size(), 2u);
  EXPECT_EQ(live.live().size(), 2u);
  EXPECT_TRUE(live.live().consistent());
  EXPECT_EQ(live.rest().y[1], 5.0f);
}

TEST(LiveMesh, LiveColumnsAreTheCallersStorageAndLeaveTheMeshAlone) {
  mesh::MeshWithStorage<4, 4> m;
  std::array<float, 4> x{}, y{}, z{};
  LiveMesh live(m, x, y, z);
  ASSERT_TRUE(m.add_vertex({1, 1, 1}).ok());
  live.live().z[0] = 7.0f;
  EXPECT_EQ(z[0], 7.0f);
  EXPECT_EQ(m.position(0).z, 1.0f);
  const LiveMesh& view = live;
  EXPECT_EQ(view.live().z[0], 7.0f);
  EXPECT_EQ(&live.mesh(), &m);
}

}  // namespace
}  // namespace twister::session
