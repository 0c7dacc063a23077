// Mesh export of the replica: OBJ reloads bit-identically (same checksum); PLY has
// the header and exact binary size; binary glTF reloads (tinygltf) with the same
// positions turned upright (+Y up, the transmitter frame's -Z by default) and
// centred, the same triangles, unit normals and a material; STL is binary and
// upright; unknown formats and unwritable paths are refused by the start-up check.
#include <gtest/gtest.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
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
  const hal::Expected<void> xyz = export_mesh(temp("m.xyz"), tetra());
  ASSERT_FALSE(xyz);
  EXPECT_NE(xyz.error().message.find("unknown mesh format"), std::string::npos);
  EXPECT_FALSE(export_mesh("/nonexistent-dir/m.ply", tetra()));
}

// STL through meshio: binary, millimetres, +Z up: the transmitter frame's -Z up
// becomes +Z (the tetrahedron's apex at z = 0.1234567 m goes to the bottom).
TEST(BridgeMeshExport, StlIsUprightInMillimetres) {
  const std::string path = temp("m.stl");
  ASSERT_TRUE(export_mesh(path, tetra()));
  std::ifstream in(path, std::ios::binary);
  std::stringstream all;
  all << in.rdbuf();
  const std::string b = all.str();
  ASSERT_EQ(b.size(), 84u + 4u * 50u);
  EXPECT_EQ(b.rfind("twister-station export, units mm, +Z up", 0), 0u);
  float lo = 1e9F;
  float hi = -1e9F;
  for (std::size_t t = 0; t < 4; ++t) {
    for (std::size_t v = 0; v < 3; ++v) {
      float z = 0;
      std::memcpy(&z, b.data() + 84 + 50 * t + 12 + 12 * v + 8, 4);
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  }
  EXPECT_NEAR(hi - lo, 123.4567F, 1e-3F);
  EXPECT_NEAR(hi + lo, 0.0F, 1e-3F);
  std::filesystem::remove(path);
}

// The float3 / uint32 data of an accessor (tightly packed, as the exporter writes).
template <typename T>
std::vector<T> accessor_data(const tinygltf::Model& model, int index, std::size_t per_item) {
  const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
  const tinygltf::BufferView& v = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
  const auto& bytes = model.buffers[static_cast<std::size_t>(v.buffer)].data;
  std::vector<T> out(a.count * per_item);
  std::memcpy(out.data(), bytes.data() + v.byteOffset + a.byteOffset, out.size() * sizeof(T));
  return out;
}

// A tetrahedron's edges are all creases (its faces meet at 109.5 degrees between
// normals): each corner is three glTF vertices, each face flat-shaded.
TEST(BridgeMeshExport, GlbReloadsWithTheSamePositionsTrianglesAndCreaseNormals) {
  const MeshData m = tetra();
  const ShadedMesh shaded = shade_with_creases(m, kDefaultCreaseAngleDeg);
  ASSERT_EQ(shaded.vertex_count(), 12u);
  const std::string path = temp("m.glb");
  ASSERT_TRUE(check_export_path(path));
  const hal::Expected<void> exported = export_mesh(path, m);
  ASSERT_TRUE(exported) << exported.error().message;
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err;
  std::string warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path)) << err;
  ASSERT_EQ(model.meshes.size(), 1u);
  const tinygltf::Primitive& p = model.meshes[0].primitives.at(0);
  EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_EQ(p.material, 0);
  const auto pos = accessor_data<float>(model, p.attributes.at("POSITION"), 3);
  ASSERT_EQ(pos.size(), 3 * shaded.vertex_count());
  // Upright: the model's up (-Z, the transmitter frame's) is glTF's +Y, so (x, y, z)
  // is (x, -z, y) moved by one offset that centres the box: x 0..0.1, -z
  // -0.1234567..0, y 0..0.1.
  const glm::vec3 offset(-0.05F, 0.1234567F / 2.0F, -0.05F);
  for (std::size_t i = 0; i < shaded.vertex_count(); ++i) {
    const std::uint32_t v = shaded.source[i];
    EXPECT_NEAR(pos[3 * i], m.x[v] + offset.x, 1e-6F);
    EXPECT_NEAR(pos[3 * i + 1], -m.z[v] + offset.y, 1e-6F);
    EXPECT_NEAR(pos[3 * i + 2], m.y[v] + offset.z, 1e-6F);
  }
  const auto indices = accessor_data<std::uint32_t>(model, p.indices, 1);
  ASSERT_EQ(indices.size(), m.indices.size());
  for (std::size_t c = 0; c < indices.size(); ++c) {
    EXPECT_EQ(shaded.source[indices[c]], m.indices[c]);  // the same triangles
  }
  const auto normals = accessor_data<float>(model, p.attributes.at("NORMAL"), 3);
  ASSERT_EQ(normals.size(), pos.size());
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const auto at = [&](std::size_t c) {
      const std::size_t i = indices[3 * t + c];
      return glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
    };
    const glm::vec3 face = glm::normalize(glm::cross(at(1) - at(0), at(2) - at(0)));
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t i = indices[3 * t + c];
      const glm::vec3 n(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
      EXPECT_NEAR(glm::dot(n, face), 1.0F, 1e-5F);  // flat: the face's own normal
    }
  }
  std::filesystem::remove(path);
}

TEST(BridgeMeshExport, StartUpCheckRefusesBadFormatsAndPaths) {
  EXPECT_TRUE(check_export_path(temp("m.obj")));
  EXPECT_TRUE(check_export_path(temp("m.gltf")));
  EXPECT_TRUE(check_export_path(temp("m.stl")));
  EXPECT_FALSE(check_export_path(temp("m.xyz")));
  EXPECT_FALSE(check_export_path(temp("m")));
  EXPECT_FALSE(check_export_path("/nonexistent-dir/m.glb"));
  const std::string folder = temp("folder.glb");
  std::filesystem::create_directory(folder);
  EXPECT_FALSE(check_export_path(folder)) << "a directory is no file";
  std::filesystem::remove(folder);
  if (::geteuid() != 0) {
    EXPECT_FALSE(check_export_path("/proc/m.glb"));
  }
}

}  // namespace
}  // namespace twister::bridge
