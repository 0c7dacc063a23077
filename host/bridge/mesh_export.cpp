#include "mesh_export.hpp"

#include <cstdio>

#include "twister/meshio/obj_file.hpp"

namespace twister::bridge {
namespace {

hal::Expected<void> export_ply(const std::string& path, const MeshData& m) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return hal::make_error(StatusCode::io_error, "cannot open " + path);
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
  if (std::fclose(f) != 0) return hal::make_error(StatusCode::io_error, "write failed: " + path);
  return {};
}

}  // namespace

hal::Expected<void> export_mesh(const std::string& path, const MeshData& m) {
  if (path.ends_with(".ply")) return export_ply(path, m);
  if (!path.ends_with(".obj")) {
    return hal::make_error(StatusCode::invalid_argument,
                           "unknown mesh format (use .obj or .ply): " + path);
  }
  const auto core = to_core_mesh(m);
  if (!core) {
    return hal::make_error(StatusCode::invalid_argument, "triangle index out of range: " + path);
  }
  std::string message;
  if (const Status s = meshio::save_obj(path, core->mesh(), message); !s.ok()) {
    return hal::Error{s, message};
  }
  return {};
}

}  // namespace twister::bridge
