// MeshData: a mesh as the display holds it (object frame, metres): columns of
// positions and 3 indices per triangle, counts checked where it is filled.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "twister/meshio/mesh_buffer.hpp"

namespace twister::bridge {

struct MeshData {
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> indices;  // 3 per triangle
  std::size_t vertex_count() const { return x.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// The data as a core mesh::Mesh (for the station's checksum and OBJ writer); null
// when a triangle index is out of range.
std::unique_ptr<meshio::MeshBuffer> to_core_mesh(const MeshData& mesh);
// mesh::Mesh::checksum() of the data; nullopt when a triangle index is out of range.
std::optional<std::uint64_t> mesh_checksum(const MeshData& mesh);

}  // namespace twister::bridge
