#include "mesh_export.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "gltf_export.hpp"
#include "twister/meshio/obj_file.hpp"
#include "vertex_normals.hpp"

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

hal::Expected<void> check_export_path(const std::string& path) {
  if (!path.ends_with(".obj") && !path.ends_with(".ply") && !path.ends_with(".glb") &&
      !path.ends_with(".gltf")) {
    return hal::make_error(StatusCode::invalid_argument,
                           "unknown mesh format (use .obj, .ply, .glb or .gltf): " + path);
  }
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    return hal::make_error(StatusCode::invalid_argument, "export path is a directory: " + path);
  }
  std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (folder.empty()) folder = ".";
  if (!std::filesystem::is_directory(folder, ec)) {
    return hal::make_error(StatusCode::io_error, "export folder does not exist: " +
                                                     folder.string() + " (for " + path + ")");
  }
  if (::access(folder.c_str(), W_OK) != 0) {
    return hal::make_error(StatusCode::io_error,
                           "export folder is not writable: " + folder.string());
  }
  return {};
}

hal::Expected<void> export_mesh(const std::string& path, const MeshData& m,
                                const std::vector<float>& normals) {
  if (path.ends_with(".ply")) return export_ply(path, m);
  if (path.ends_with(".glb") || path.ends_with(".gltf")) {
    if (normals.size() == 3 * m.vertex_count()) {
      return export_gltf(path, m, normals, path.ends_with(".glb"));
    }
    std::vector<float> computed;
    compute_vertex_normals(m, computed);
    return export_gltf(path, m, computed, path.ends_with(".glb"));
  }
  if (!path.ends_with(".obj")) {
    return hal::make_error(StatusCode::invalid_argument,
                           "unknown mesh format (use .obj, .ply, .glb or .gltf): " + path);
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
