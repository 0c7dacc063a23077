#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister::meshio {
namespace {

TEST(MeshIo, SaveLoadRoundTripIsBitIdentical) {
  MeshBuffer sphere(sphere_vertices(12, 17), sphere_triangles(12, 17));
  ASSERT_TRUE(make_sphere(sphere.mesh(), 12, 17, 0.3f).ok());
  // Awkward floats: every bit pattern must survive the text round trip.
  sphere.mesh().set_position(3, {1.0f / 3.0f, -1e-38f, 123456.789f});
  const auto back = parse_obj(obj_text(sphere.mesh()));
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->buffer->mesh().checksum(), sphere.mesh().checksum());
}

TEST(MeshIo, SaveAndLoadAFile) {
  MeshBuffer grid(grid_vertices(9), grid_triangles(9));
  ASSERT_TRUE(make_grid(grid.mesh(), 9, 0.5f).ok());
  const auto path = std::filesystem::temp_directory_path() / "twister_meshio_test.obj";
  const auto saved = save_obj(path, grid.mesh());
  ASSERT_TRUE(saved) << saved.error().message;
  const auto back = load_obj(path, {.spare_vertices = 10, .spare_triangles = 20});
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->buffer->mesh().checksum(), grid.mesh().checksum());
  EXPECT_EQ(back->buffer->mesh().vertex_capacity(), 81u + 10u);
  std::filesystem::remove(path);
}

TEST(MeshIo, PolygonsAreTriangulated) {
  const auto quad = parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  ASSERT_TRUE(quad) << quad.error().message;
  EXPECT_EQ(quad->buffer->mesh().triangle_count(), 2u);
}

TEST(MeshIo, BadFilesAreClearErrors) {
  EXPECT_EQ(parse_obj("").error().status.code(), StatusCode::invalid_argument);
  const auto bad_index = parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n");
  EXPECT_EQ(bad_index.error().status.code(), StatusCode::invalid_argument);
  EXPECT_NE(bad_index.error().message.find("does not exist"), std::string::npos)
      << bad_index.error().message;
  const auto nan = parse_obj("v 1 0 0\nv 0 0 nan\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(nan.error().status.code(), StatusCode::invalid_argument);
  EXPECT_NE(nan.error().message.find("line 2"), std::string::npos) << nan.error().message;
  EXPECT_EQ(parse_obj("v 1 0\nv 0 0 0\nv 0 1 0\nf 1 2 3\n").error().status.code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(parse_obj("v 1 0 0x\nv 0 0 0\nv 0 1 0\nf 1 2 3\n").error().status.code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(load_obj("/nonexistent/file.obj").error().status.code(), StatusCode::io_error);
}

TEST(MeshIo, GeneratorsFillExactlyTheirCounts) {
  MeshBuffer small(10, 10);
  EXPECT_EQ(make_grid(small.mesh(), 9, 1.0f).code(), StatusCode::resource_exhausted);
  EXPECT_EQ(make_grid(small.mesh(), 1, 1.0f).code(), StatusCode::invalid_argument);
  MeshBuffer s(sphere_vertices(8, 8), sphere_triangles(8, 8));
  ASSERT_TRUE(make_sphere(s.mesh(), 8, 8, 2.0f).ok());
  EXPECT_EQ(s.mesh().vertex_count(), sphere_vertices(8, 8));
  EXPECT_EQ(s.mesh().triangle_count(), sphere_triangles(8, 8));
  for (std::uint32_t i = 0; i < s.mesh().vertex_count(); ++i) {
    const glm::vec3 p = s.mesh().position(i);
    EXPECT_NEAR(std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z), 2.0f, 1e-5f);
  }
}

}  // namespace
}  // namespace twister::meshio
