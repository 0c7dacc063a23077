// Mesh export of the replica: OBJ reloads bit-identically (same checksum); PLY has
// the header and exact binary size; unknown extensions are refused.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "mesh_export.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister::bridge {
namespace {

MeshData tetra() {
  MeshData m;
  m.x = {0.0F, 0.1F, 0.0F, 0.0F};
  m.y = {0.0F, 0.0F, 0.1F, 0.0F};
  m.z = {0.0F, 0.0F, 0.0F, 0.1234567F};
  m.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  return m;
}

std::string temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("twister-bridge-" + std::to_string(::getpid()) + "-" + name))
      .string();
}

TEST(BridgeMeshExport, ObjReloadsBitIdentical) {
  const MeshData m = tetra();
  const std::string path = temp("m.obj");
  const hal::Expected<void> exported = export_mesh(path, m);
  ASSERT_TRUE(exported) << exported.error().message;
  const auto back = meshio::load_obj(path);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->buffer->mesh().checksum(), *mesh_checksum(m));
  std::filesystem::remove(path);
}

TEST(BridgeMeshExport, PlyHeaderAndSize) {
  const MeshData m = tetra();
  const std::string path = temp("m.ply");
  const hal::Expected<void> exported = export_mesh(path, m);
  ASSERT_TRUE(exported) << exported.error().message;
  std::ifstream in(path, std::ios::binary);
  std::stringstream all;
  all << in.rdbuf();
  const std::string text = all.str();
  const auto end = text.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  EXPECT_NE(text.find("element vertex 4\n"), std::string::npos);
  EXPECT_NE(text.find("element face 4\n"), std::string::npos);
  EXPECT_EQ(text.size() - (end + 11), 4u * 12u + 4u * 13u);
  std::filesystem::remove(path);
}

TEST(BridgeMeshExport, UnknownFormatAndBadPathAreErrors) {
  const hal::Expected<void> stl = export_mesh(temp("m.stl"), tetra());
  ASSERT_FALSE(stl);
  EXPECT_NE(stl.error().message.find("unknown mesh format"), std::string::npos);
  EXPECT_FALSE(export_mesh("/nonexistent-dir/m.ply", tetra()));
}

}  // namespace
}  // namespace twister::bridge
