#include "mesh_export.hpp"

#include <cstdio>

#include "twister/meshio/obj_file.hpp"

namespace twister::bridge {
namespace {

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
  if (path.ends_with(".ply")) return export_ply(path, m, message);
  if (!path.ends_with(".obj")) {
    message = "unknown mesh format (use .obj or .ply): " + path;
    return false;
  }
  const auto core = to_core_mesh(m);
  if (!core) {
    message = "triangle index out of range: " + path;
    return false;
  }
  return meshio::save_obj(path, core->mesh(), message).ok();
}

}  // namespace twister::bridge
