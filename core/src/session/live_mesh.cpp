#include "twister/session/live_mesh.hpp"

#include "twister/base/assert.hpp"

namespace twister::session {

LiveMesh::LiveMesh(mesh::Mesh& mesh, std::span<float> live_x, std::span<float> live_y,
                   std::span<float> live_z)
    : mesh_(mesh), live_x_(live_x), live_y_(live_y), live_z_(live_z) {
  TWISTER_ASSERT(live_x.size() >= mesh.vertex_capacity() &&
                 live_y.size() >= mesh.vertex_capacity() &&
                 live_z.size() >= mesh.vertex_capacity());
}

math::ConstVertexColumns LiveMesh::rest() const {
  const mesh::Mesh& m = mesh_;
  return {m.x(), m.y(), m.z()};
}

math::VertexColumns LiveMesh::live() {
  const std::size_t n = mesh_.vertex_count();
  return {live_x_.first(n), live_y_.first(n), live_z_.first(n)};
}

math::ConstVertexColumns LiveMesh::live() const {
  const std::size_t n = mesh_.vertex_count();
  return {live_x_.first(n), live_y_.first(n), live_z_.first(n)};
}

}  // namespace twister::session
