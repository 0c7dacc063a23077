#include "mesh_export.hpp"

#include <cstdio>
#include <vector>

#include "twister/meshio/obj_file.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::bridge {
namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

bool export_ply(const std::string& path, const MeshData& m, std::string& message) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) {
    message = "cannot open " + path;
    return false;
  }
  std::fprintf(f,
               "ply\nformat binary_little_endian 1.0\ncomment twister-bridge export (metres)\n"
               "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
               "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n",
               m.vertex_count(), m.triangle_count());
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const float p[3] = {m.x[i], m.y[i], m.z[i]};
    std::fwrite(p, sizeof(float), 3, f);
  }
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const unsigned char three = 3;
    std::fwrite(&three, 1, 1, f);
    std::fwrite(&m.indices[3 * t], sizeof(std::uint32_t), 3, f);
  }
  if (std::fclose(f) != 0) {
    message = "write failed: " + path;
    return false;
  }
  return true;
}

}  // namespace

bool export_mesh(const std::string& path, const MeshData& m, std::string& message) {
  if (ends_with(path, ".ply")) return export_ply(path, m, message);
  if (!ends_with(path, ".obj")) {
    message = "unknown mesh format (use .obj or .ply): " + path;
    return false;
  }
  std::vector<float> x(m.x), y(m.y), z(m.z);
  std::vector<std::uint32_t> idx(m.indices.size());
  mesh::Mesh mesh(x, y, z, idx);
  for (std::size_t i = 0; i < m.vertex_count(); ++i) (void)mesh.add_vertex({m.x[i], m.y[i], m.z[i]});
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    (void)mesh.add_triangle(m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]);
  }
  return meshio::save_obj(path, mesh, message).ok();
}

}  // namespace twister::bridge
