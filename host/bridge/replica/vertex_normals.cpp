#include "vertex_normals.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace twister::bridge {

void compute_vertex_normals(const MeshData& mesh, std::vector<float>& out) {
  const std::size_t n = mesh.vertex_count();
  std::vector<glm::dvec3> sum(n, glm::dvec3(0.0));
  const auto at = [&mesh](std::uint32_t i) { return glm::dvec3(mesh.x[i], mesh.y[i], mesh.z[i]); };
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::uint32_t a = mesh.indices[3 * t];
    const std::uint32_t b = mesh.indices[3 * t + 1];
    const std::uint32_t c = mesh.indices[3 * t + 2];
    if (a >= n || b >= n || c >= n) continue;  // verified meshes have none
    // The cross product's length is twice the area: area weighting for free.
    const glm::dvec3 face = glm::cross(at(b) - at(a), at(c) - at(a));
    sum[a] += face;
    sum[b] += face;
    sum[c] += face;
  }
  out.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double len = glm::length(sum[i]);
    const glm::dvec3 u = len > 0.0 && std::isfinite(len) ? sum[i] / len : glm::dvec3(0, 0, 1);
    out[3 * i] = static_cast<float>(u.x);
    out[3 * i + 1] = static_cast<float>(u.y);
    out[3 * i + 2] = static_cast<float>(u.z);
  }
}

}  // namespace twister::bridge
