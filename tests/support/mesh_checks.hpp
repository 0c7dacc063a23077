// Mesh checks the refinement tests share: edge-triangle incidence (conforming,
// manifold, consistently oriented) and the midpoint error of every edge.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "twister/mesh/mesh.hpp"
#include "twister/mesh/point_warp.hpp"

namespace twister::test_support {

struct EdgeIncidence {
  std::size_t edges = 0;           // undirected edges
  std::size_t boundary = 0;        // edges of one triangle
  std::size_t interior = 0;        // edges of exactly two triangles
  std::size_t nonmanifold = 0;     // edges of three or more triangles
  std::size_t same_direction = 0;  // directed edges used twice (inconsistent orientation)
  std::size_t degenerate = 0;      // triangles repeating a vertex
  std::size_t unused_vertices = 0;
};

// Every undirected edge (a < b) with the number of triangles on it.
inline std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge_counts(const mesh::Mesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> counts;
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    const auto v = m.triangle(t);
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = v[i], b = v[(i + 1) % 3];
      ++counts[{std::min(a, b), std::max(a, b)}];
    }
  }
  return counts;
}

inline EdgeIncidence edge_incidence(const mesh::Mesh& m) {
  EdgeIncidence r;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::vector<bool> used(m.vertex_count(), false);
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    const auto v = m.triangle(t);
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) ++r.degenerate;
    for (int i = 0; i < 3; ++i) {
      used[v[i]] = true;
      if (++directed[{v[i], v[(i + 1) % 3]}] == 2) ++r.same_direction;
    }
  }
  for (const auto& [edge, count] : edge_counts(m)) {
    ++r.edges;
    if (count == 1) ++r.boundary;
    if (count == 2) ++r.interior;
    if (count > 2) ++r.nonmanifold;
  }
  r.unused_vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), false));
  return r;
}

// A closed, conforming, manifold, consistently oriented triangle mesh: every edge has
// exactly two triangles (a T-junction leaves edges with one), V - E + F = 2.
inline bool closed_manifold(const mesh::Mesh& m) {
  const EdgeIncidence r = edge_incidence(m);
  const auto euler = static_cast<long>(m.vertex_count()) - static_cast<long>(r.edges) +
                     static_cast<long>(m.triangle_count());
  return r.boundary == 0 && r.nonmanifold == 0 && r.same_direction == 0 && r.degenerate == 0 &&
         r.unused_vertices == 0 && euler == 2;
}

// The largest |(S(A) + S(B))/2 - S((A + B)/2)| over the edges of `rest` (rest
// positions of the refined topology).
inline double max_midpoint_error(const mesh::Mesh& rest, const mesh::PointWarp& warp) {
  double worst = 0.0;
  for (const auto& [edge, count] : edge_counts(rest)) {
    const glm::dvec3 a(rest.position(edge.first));
    const glm::dvec3 b(rest.position(edge.second));
    const glm::dvec3 chord = 0.5 * (warp.warp(a) + warp.warp(b));
    const glm::dvec3 d = chord - warp.warp(0.5 * (a + b));
    worst = std::max(worst, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z));
  }
  return worst;
}

}  // namespace twister::test_support
