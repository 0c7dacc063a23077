#include "mesh_export.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <span>
#include <string>

#include "twister/hal/output_file.hpp"
#include "twister/hal/posix_file_sink.hpp"
#include "twister/meshio/mesh_export.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister::bridge {
namespace {

// Bytes through PosixFileSink: atomic, under the programs' output rule.
hal::Expected<void> write_file(const std::string& path, const std::string& out, bool force) {
  hal::OutputRule rule{hal::OutputKind::obj, force};
  if (!hal::output_kind_of(path, rule.kind)) {
    return hal::make_error(StatusCode::invalid_argument, "unknown file kind: " + path);
  }
  return hal::write_output_file(path, out, rule);
}

// Binary PLY.
hal::Expected<void> export_ply(const std::string& path, const MeshData& m, bool force) {
  std::string out;
  char header[512];
  const int n =
      std::snprintf(header, sizeof header,
                    "ply\nformat binary_little_endian 1.0\ncomment twister-bridge export (metres)\n"
                    "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n",
                    m.vertex_count(), m.triangle_count());
  out.append(header, static_cast<std::size_t>(n));
  auto put = [&out](const void* data, std::size_t bytes) {
    out.append(static_cast<const char*>(data), bytes);
  };
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    const float p[3] = {m.x[i], m.y[i], m.z[i]};
    put(p, sizeof p);
  }
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const unsigned char three = 3;
    put(&three, 1);
    put(&m.indices[3 * t], 3 * sizeof(std::uint32_t));
  }
  return write_file(path, out, force);
}

}  // namespace

hal::Expected<void> check_export_path(const std::string& path, bool force) {
  if (!path.ends_with(".obj") && !path.ends_with(".ply") && !path.ends_with(".glb") &&
      !path.ends_with(".gltf") && !path.ends_with(".stl")) {
    return hal::make_error(StatusCode::invalid_argument,
                           "unknown mesh format (use .obj, .ply, .glb, .gltf or .stl): " + path);
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
  hal::OutputRule rule{hal::OutputKind::obj, force};
  hal::output_kind_of(path, rule.kind);
  return hal::check_output_path(path, rule);
}

hal::Expected<void> export_mesh(const std::string& path, const MeshData& m,
                                const ShadedMesh& shaded, bool force, glm::vec3 up) {
  if (path.ends_with(".ply")) return export_ply(path, m, force);
  const bool gltf = path.ends_with(".glb") || path.ends_with(".gltf");
  if (!gltf && !path.ends_with(".obj") && !path.ends_with(".stl")) {
    return hal::make_error(StatusCode::invalid_argument,
                           "unknown mesh format (use .obj, .ply, .glb, .gltf or .stl): " + path);
  }
  const auto core = to_core_mesh(m);
  if (!core) {
    return hal::make_error(StatusCode::invalid_argument, "triangle index out of range: " + path);
  }
  if (path.ends_with(".obj")) return meshio::save_obj(path, core->mesh(), force);
  meshio::ExportOptions options;
  options.up = up;
  options.force = force;
  if (path.ends_with(".stl")) {
    auto written = meshio::write_stl(path, core->mesh(), options);
    if (!written) return written.error();
    return {};
  }
  if (shaded.mesh_vertices != m.vertex_count()) {
    return hal::make_error(StatusCode::invalid_argument, "shading of another mesh: " + path);
  }
  const meshio::GlbShading shading{shaded.source, shaded.normals, shaded.indices};
  hal::Expected<std::string> bytes =
      meshio::glb_bytes(core->mesh(), options, shading, path.ends_with(".glb"));
  if (!bytes) return hal::Error{bytes.error().status, path + ": " + bytes.error().message};
  return write_file(path, *bytes, force);
}

hal::Expected<void> export_mesh(const std::string& path, const MeshData& m, bool force,
                                glm::vec3 up) {
  return export_mesh(path, m, shade_with_creases(m, kDefaultCreaseAngleDeg), force, up);
}

}  // namespace twister::bridge
