// TriangleAdjacency: which triangle lies across each edge of a Mesh, in fixed storage.
// Half-edge h = 3 t + i is edge i of triangle t, from its vertex i to vertex (i+1)%3.
// twin(h) is the half-edge of the other triangle on that edge (either orientation),
// kBoundary when no other triangle has it, kNonManifold when more than two have it
// or a triangle repeats a vertex (such edges must never be split: a split could not
// reach every triangle on them). build() is O(triangles x valence) and allocation
// free: a vertex -> triangle table is built in the scratch spans first.
// Memory: caller-owned spans, at least the capacities of the meshes it is built
// for (see fits()). Not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/status.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::mesh {

inline constexpr std::uint32_t kBoundary = 0xffffffffu;
inline constexpr std::uint32_t kNonManifold = 0xfffffffeu;

struct TriangleAdjacencyStorage {
  std::span<std::uint32_t> twins;           // 3 per triangle of capacity
  std::span<std::uint32_t> vertex_offsets;  // vertex capacity + 1 (scratch of build())
  std::span<std::uint32_t> incident;        // 3 per triangle of capacity (scratch)
};

class TriangleAdjacency {
 public:
  explicit TriangleAdjacency(TriangleAdjacencyStorage storage) : storage_(storage) {}

  // The storage holds every triangle and vertex `mesh` can ever have.
  bool fits(const Mesh& mesh) const;
  // Twins of every half-edge of `mesh`. resource_exhausted: !fits(mesh).
  Status build(const Mesh& mesh);

  std::uint32_t twin(std::uint32_t h) const { return storage_.twins[h]; }
  // Makes h and g twins of each other; g may be kBoundary or kNonManifold (then
  // only h is set).
  void link(std::uint32_t h, std::uint32_t g);

 private:
  std::uint32_t find_twin(std::span<const std::uint32_t> indices, std::uint32_t h) const;

  TriangleAdjacencyStorage storage_;
};

}  // namespace twister::mesh
