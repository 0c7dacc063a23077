// MeshBuffer: host-side owner of a core mesh::Mesh's storage (std::vector columns),
// sized once; the Mesh itself never grows past the capacity given here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "twister/mesh/mesh.hpp"

namespace twister::meshio {

class MeshBuffer {
 public:
  MeshBuffer(std::size_t vertex_capacity, std::size_t triangle_capacity)
      : x_(vertex_capacity),
        y_(vertex_capacity),
        z_(vertex_capacity),
        indices_(3 * triangle_capacity),
        mesh_(x_, y_, z_, indices_) {}
  MeshBuffer(const MeshBuffer&) = delete;
  MeshBuffer& operator=(const MeshBuffer&) = delete;

  mesh::Mesh& mesh() { return mesh_; }
  const mesh::Mesh& mesh() const { return mesh_; }

 private:
  std::vector<float> x_, y_, z_;
  std::vector<std::uint32_t> indices_;
  mesh::Mesh mesh_;
};

}  // namespace twister::meshio
