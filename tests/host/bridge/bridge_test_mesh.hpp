// Meshes for the bridge's tests: a UV sphere as MeshData, fed to a replica as the
// station sends a full mesh, and a pixel comparison of two RGBA pictures.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "scene_replica.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace twister::bridge::test {

// A core mesh as the display holds it.
inline MeshData to_mesh_data(const mesh::Mesh& m) {
  MeshData d;
  d.x.assign(m.x().begin(), m.x().end());
  d.y.assign(m.y().begin(), m.y().end());
  d.z.assign(m.z().begin(), m.z().end());
  d.indices.assign(m.triangle_indices().begin(), m.triangle_indices().end());
  return d;
}

inline MeshData sphere_mesh(float radius_m, std::size_t rings = 48, std::size_t segments = 64) {
  static mesh::MeshWithStorage<8192, 16384> m;
  m.clear();
  EXPECT_TRUE(meshio::make_sphere(m, rings, segments, radius_m).ok());
  return to_mesh_data(m);
}

// Feeds `m` to the replica as the station would (full mesh, version 1).
inline void load_mesh(SceneReplica& r, const MeshData& m) {
  link::MeshBegin b;
  b = {true, 0, 1, static_cast<std::uint32_t>(m.vertex_count()),
       static_cast<std::uint32_t>(m.triangle_count())};
  (void)r.apply(b);
  link::Vertices v;
  for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
    v.items[v.count++] = {i, m.x[i], m.y[i], m.z[i]};
    if (v.count == link::kMaxVerticesPerChunk || i + 1 == m.vertex_count()) {
      (void)r.apply(v);
      v.count = 0;
    }
  }
  link::Triangles t;
  for (std::uint32_t k = 0; k < m.triangle_count(); k += link::kMaxTrianglesPerChunk) {
    const auto n = std::min<std::size_t>(link::kMaxTrianglesPerChunk, m.triangle_count() - k);
    t.first = k;
    t.count = static_cast<std::uint16_t>(n);
    std::copy_n(m.indices.begin() + 3 * static_cast<std::ptrdiff_t>(k), 3 * n, t.indices.begin());
    (void)r.apply(t);
  }
  link::MeshEnd e;
  e = {1, *mesh_checksum(m)};
  ASSERT_FALSE(r.apply(e));
  ASSERT_EQ(r.version(), 1u);
}

// Fraction of pixels whose channels differ by more than `tol` (RGBA, same size).
inline double differing(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b,
                        int tol) {
  std::size_t n = 0;
  for (std::size_t p = 0; p < a.size(); p += 4) {
    for (std::size_t c = 0; c < 3; ++c) {
      if (std::abs(int{a[p + c]} - int{b[p + c]}) > tol) {
        ++n;
        break;
      }
    }
  }
  return static_cast<double>(n) / static_cast<double>(a.size() / 4);
}

}  // namespace twister::bridge::test
