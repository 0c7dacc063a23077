#include "twister/mesh/vertex_normals.hpp"

#include <cmath>
#include <glm/geometric.hpp>

namespace twister::mesh {

Status compute_vertex_normals(const Mesh& mesh, NormalColumns out) {
  const std::size_t n = mesh.vertex_count();
  if (out.x.size() < n || out.y.size() < n || out.z.size() < n) {
    return StatusCode::invalid_argument;
  }
  for (std::size_t v = 0; v < n; ++v) out.x[v] = out.y[v] = out.z[v] = 0.0f;
  const auto idx = mesh.triangle_indices();
  for (std::size_t k = 0; k < idx.size(); k += 3) {
    const glm::vec3 a = mesh.position(idx[k]);
    const glm::vec3 face = glm::cross(mesh.position(idx[k + 1]) - a, mesh.position(idx[k + 2]) - a);
    for (std::size_t c = 0; c < 3; ++c) {
      out.x[idx[k + c]] += face.x;
      out.y[idx[k + c]] += face.y;
      out.z[idx[k + c]] += face.z;
    }
  }
  for (std::size_t v = 0; v < n; ++v) {
    const float length = std::sqrt(out.x[v] * out.x[v] + out.y[v] * out.y[v] + out.z[v] * out.z[v]);
    if (!(length > 0.0f) || !std::isfinite(length)) {
      out.x[v] = out.y[v] = out.z[v] = 0.0f;
      continue;
    }
    out.x[v] /= length;
    out.y[v] /= length;
    out.z[v] /= length;
  }
  return ok_status();
}

}  // namespace twister::mesh
