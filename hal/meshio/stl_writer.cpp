// Binary STL: the 80-byte header (our prefix, units and up stated), the triangle
// count, then per triangle its unit normal, three vertices (float32, little-endian,
// millimetres, +Z up, bounding box centred on the origin) and a zero attribute word.
#include <cstdio>
#include <cstring>
#include <glm/geometric.hpp>

#include "export_file.hpp"
#include "export_frame.hpp"
#include "twister/meshio/mesh_export.hpp"

namespace twister::meshio {
namespace {

constexpr double kMillimetresPerMetre = 1000.0;

void put_u32(std::string& out, std::uint32_t v) {
  const unsigned char b[4] = {static_cast<unsigned char>(v), static_cast<unsigned char>(v >> 8),
                              static_cast<unsigned char>(v >> 16),
                              static_cast<unsigned char>(v >> 24)};
  out.append(reinterpret_cast<const char*>(b), 4);
}

void put_f32(std::string& out, double v) {
  const auto f = static_cast<float>(v);
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, 4);
  put_u32(out, bits);
}

void put_vec(std::string& out, glm::dvec3 v) {
  put_f32(out, v.x);
  put_f32(out, v.y);
  put_f32(out, v.z);
}

std::string stl_bytes(const mesh::Mesh& mesh, const internal::UprightFrame& frame) {
  std::string out;
  out.reserve(84 + 50 * mesh.triangle_count());
  char header[81] = {};
  std::snprintf(header, sizeof header, "%s, units mm, +Z up, centred; %zu triangles",
                hal::kStlHeaderPrefix, mesh.triangle_count());
  out.append(header, 80);
  put_u32(out, static_cast<std::uint32_t>(mesh.triangle_count()));
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto v = mesh.triangle(t);
    glm::dvec3 p[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = frame.apply(glm::dvec3(mesh.position(v[static_cast<std::size_t>(k)]))) *
             kMillimetresPerMetre;
    }
    const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    const double len = glm::length(n);
    put_vec(out, len > 0.0 ? n / len : glm::dvec3(0.0));
    for (const glm::dvec3& q : p) put_vec(out, q);
    out.append(2, '\0');
  }
  return out;
}

}  // namespace

hal::Expected<ExportReport> write_stl(const std::string& path, const mesh::Mesh& mesh,
                                      const ExportOptions& options) {
  if (mesh.triangle_count() == 0) {
    return hal::make_error(StatusCode::invalid_argument, path + ": the mesh has no triangles");
  }
  auto frame = internal::upright_frame(mesh, options.up, glm::dvec3(0, 0, 1));
  if (!frame) return hal::Error{frame.error().status, path + ": " + frame.error().message};
  ExportReport report;
  report.path = path;
  report.check = check_mesh(mesh, options.check);
  report.units = "mm";
  report.size = (frame->hi - frame->lo) * kMillimetresPerMetre;
  report.moved_by = frame->offset;
  const std::string bytes = stl_bytes(mesh, *frame);
  report.bytes = bytes.size();
  if (auto written = internal::write_export_file(path, bytes, hal::OutputKind::stl, options.force);
      !written) {
    return written.error();
  }
  return report;
}

}  // namespace twister::meshio
