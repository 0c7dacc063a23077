// Mesh: a triangle mesh with fixed capacity over caller-owned storage.
// Vertices are structure-of-arrays float columns (x, y, z; metres, object frame) so
// warp kernels take spans over them; triangles are three uint32 vertex indices.
// No allocation: capacity is the size of the spans given at construction;
// MeshWithStorage<V, T> owns the arrays. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>

#include "twister/base/result.hpp"

namespace twister::mesh {

class Mesh {
 public:
  // x, y, z must have the same size (the vertex capacity); triangle_indices holds
  // 3 indices per triangle (capacity = size / 3). The mesh starts empty.
  Mesh(std::span<float> x, std::span<float> y, std::span<float> z,
       std::span<std::uint32_t> triangle_indices);

  std::size_t vertex_capacity() const { return x_.size(); }
  std::size_t triangle_capacity() const { return indices_.size() / 3; }
  std::size_t vertex_count() const { return vertex_count_; }
  std::size_t triangle_count() const { return triangle_count_; }

  // Appends a vertex; returns its index. resource_exhausted: capacity reached.
  Result<std::uint32_t> add_vertex(glm::vec3 position_m);
  // Appends a triangle. invalid_argument: an index >= vertex_count().
  // resource_exhausted: capacity reached. The mesh is unchanged on error.
  Result<std::uint32_t> add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  void clear();

  // Columns over the live vertices (vertex_count() long).
  std::span<float> x() { return x_.first(vertex_count_); }
  std::span<float> y() { return y_.first(vertex_count_); }
  std::span<float> z() { return z_.first(vertex_count_); }
  std::span<const float> x() const { return x_.first(vertex_count_); }
  std::span<const float> y() const { return y_.first(vertex_count_); }
  std::span<const float> z() const { return z_.first(vertex_count_); }
  // 3 * triangle_count() indices.
  std::span<const std::uint32_t> triangle_indices() const {
    return indices_.first(3 * triangle_count_);
  }

  // Position of vertex i (i < vertex_count(), asserted).
  glm::vec3 position(std::uint32_t i) const;
  void set_position(std::uint32_t i, glm::vec3 position_m);
  // Vertex indices of triangle t (t < triangle_count(), asserted).
  std::array<std::uint32_t, 3> triangle(std::uint32_t t) const;
  // Rewrites triangle t in place (t < triangle_count(), indices < vertex_count(),
  // asserted): refinement splits triangles, undo puts them back.
  void set_triangle(std::uint32_t t, const std::array<std::uint32_t, 3>& v);

  // Sets the counts (undo and redo of refinement): shrinking drops the last vertices
  // and triangles; growing exposes whatever the storage holds there, which the
  // caller then sets. resource_exhausted: beyond capacity (nothing changed).
  Status resize(std::size_t vertices, std::size_t triangles);

  // Copies another mesh. resource_exhausted: it does not fit (this mesh unchanged).
  Status copy_from(const Mesh& other);

  // 64-bit FNV-1a over the counts, the exact bit patterns of the positions and the
  // indices: equal checksums <=> (practically) bit-identical meshes.
  std::uint64_t checksum() const;

  // Changes with every change of the triangles or the counts (add_triangle,
  // set_triangle, resize, copy_from, clear; not positions, not add_vertex): a
  // structure built from the topology (the refiner's adjacency) is still valid while
  // it is the same. Not part of the checksum.
  std::uint64_t topology_version() const { return topology_version_; }

 private:
  std::span<float> x_;
  std::span<float> y_;
  std::span<float> z_;
  std::span<std::uint32_t> indices_;
  std::size_t vertex_count_ = 0;
  std::size_t triangle_count_ = 0;
  std::uint64_t topology_version_ = 0;
};

// A Mesh owning its storage. Large: place it in static storage or the arena.
template <std::size_t kVertices, std::size_t kTriangles>
class MeshWithStorage : public Mesh {
 public:
  MeshWithStorage() : Mesh(x_storage_, y_storage_, z_storage_, index_storage_) {}
  MeshWithStorage(const MeshWithStorage&) = delete;
  MeshWithStorage& operator=(const MeshWithStorage&) = delete;

 private:
  std::array<float, kVertices> x_storage_{};
  std::array<float, kVertices> y_storage_{};
  std::array<float, kVertices> z_storage_{};
  std::array<std::uint32_t, 3 * kTriangles> index_storage_{};
};

}  // namespace twister::mesh
