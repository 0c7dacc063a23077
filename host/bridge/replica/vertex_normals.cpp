#include "vertex_normals.hpp"

#include "twister/mesh/vertex_normals.hpp"

namespace twister::bridge {

void compute_vertex_normals(const MeshData& mesh, std::vector<float>& out) {
  const std::size_t n = mesh.vertex_count();
  out.assign(3 * n, 0.0F);
  // The station's own function (core mesh), on the replica's copy.
  const auto core = to_core_mesh(mesh);
  if (!core) return;  // a triangle index out of range: verified meshes have none
  std::vector<float> x(n), y(n), z(n);
  if (!mesh::compute_vertex_normals(core->mesh(), {x, y, z}).ok()) return;
  for (std::size_t i = 0; i < n; ++i) {
    out[3 * i] = x[i];
    out[3 * i + 1] = y[i];
    out[3 * i + 2] = z[i];
  }
}

}  // namespace twister::bridge
