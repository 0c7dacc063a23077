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
  const ObjLoad back = parse_obj(obj_text(sphere.mesh()));
  ASSERT_TRUE(back.status.ok()) << back.message;
  EXPECT_EQ(back.buffer->mesh().checksum(), sphere.mesh().checksum());
}

TEST(MeshIo, SaveAndLoadAFile) {
  MeshBuffer grid(grid_vertices(9), grid_triangles(9));
  ASSERT_TRUE(make_grid(grid.mesh(), 9, 0.5f).ok());
  const auto path = std::filesystem::temp_directory_path() / "twister_meshio_test.obj";
  std::string message;
  ASSERT_TRUE(save_obj(path, grid.mesh(), message).ok()) << message;
  const ObjLoad back = load_obj(path, 10, 20);
  ASSERT_TRUE(back.status.ok()) << back.message;
  EXPECT_EQ(back.buffer->mesh().checksum(), grid.mesh().checksum());
  EXPECT_EQ(back.buffer->mesh().vertex_capacity(), 81u + 10u);
  std::filesystem::remove(path);
}

TEST(MeshIo, PolygonsAreTriangulated) {
  const ObjLoad quad = parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  ASSERT_TRUE(quad.status.ok()) << quad.message;
  EXPECT_EQ(quad.buffer->mesh().triangle_count(), 2u);
}

TEST(MeshIo, BadFilesAreClearErrors) {
  EXPECT_EQ(parse_obj("").status.code(), StatusCode::invalid_argument);
  const ObjLoad bad_index = parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n");
  EXPECT_EQ(bad_index.status.code(), StatusCode::invalid_argument);
  EXPECT_NE(bad_index.message.find("does not exist"), std::string::npos) << bad_index.message;
  const ObjLoad nan = parse_obj("v 1 0 0\nv 0 0 nan\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(nan.status.code(), StatusCode::invalid_argument);
  EXPECT_NE(nan.message.find("line 2"), std::string::npos) << nan.message;
  EXPECT_EQ(parse_obj("v 1 0\nv 0 0 0\nv 0 1 0\nf 1 2 3\n").status.code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(parse_obj("v 1 0 0x\nv 0 0 0\nv 0 1 0\nf 1 2 3\n").status.code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(load_obj("/nonexistent/file.obj").status.code(), StatusCode::io_error);
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
