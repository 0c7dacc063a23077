// check_mesh: edges by sorting (each triangle's three edges as unordered pairs with
// their direction), degenerate triangles, and the self-intersection count
// (mesh_intersections.cpp).
#include <algorithm>
#include <cstdio>
#include <glm/geometric.hpp>
#include <vector>

#include "mesh_intersections.hpp"
#include "twister/meshio/mesh_export.hpp"

namespace twister::meshio {
namespace {

struct HalfEdge {
  std::uint64_t key;  // (min << 32) | max
  bool forward;       // runs min -> max in its triangle
};

void count_edges(const mesh::Mesh& mesh, MeshCheck& check) {
  const auto idx = mesh.triangle_indices();
  std::vector<HalfEdge> edges;
  edges.reserve(idx.size());
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = idx[t + k];
      const std::uint32_t b = idx[t + (k + 1) % 3];
      if (a == b) continue;  // a degenerate triangle's collapsed edge
      const std::uint64_t lo = std::min(a, b);
      const std::uint64_t hi = std::max(a, b);
      edges.push_back({(lo << 32) | hi, a < b});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const HalfEdge& l, const HalfEdge& r) { return l.key < r.key; });
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    std::size_t forward = 0;
    while (j < edges.size() && edges[j].key == edges[i].key) {
      if (edges[j++].forward) ++forward;
    }
    const std::size_t n = j - i;
    ++check.edges;
    if (n == 1) ++check.open_edges;
    if (n >= 3) ++check.non_manifold_edges;
    if (n == 2 && forward != 1) ++check.misoriented_edges;
    i = j;
  }
}

void count_degenerate(const mesh::Mesh& mesh, MeshCheck& check) {
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto v = mesh.triangle(t);
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
      ++check.degenerate_triangles;
      continue;
    }
    const glm::dvec3 a(mesh.position(v[0]));
    const glm::dvec3 e1 = glm::dvec3(mesh.position(v[1])) - a;
    const glm::dvec3 e2 = glm::dvec3(mesh.position(v[2])) - a;
    const double scale = std::max(glm::dot(e1, e1), glm::dot(e2, e2));
    const glm::dvec3 n = glm::cross(e1, e2);
    // Zero area, or an area below float resolution of its edges (a needle or sliver
    // whose normal is noise).
    if (scale == 0.0 || glm::dot(n, n) <= 1e-24 * scale * scale) ++check.degenerate_triangles;
  }
}

}  // namespace

MeshCheck check_mesh(const mesh::Mesh& mesh, const CheckOptions& options) {
  MeshCheck check;
  check.vertices = mesh.vertex_count();
  check.triangles = mesh.triangle_count();
  count_edges(mesh, check);
  count_degenerate(mesh, check);
  if (options.intersections && check.triangles <= options.max_intersection_triangles) {
    check.self_intersections = internal::count_self_intersections(mesh);
    check.intersections_checked = true;
  }
  return check;
}

std::string describe(const MeshCheck& c) {
  char line[320];
  char crossings[64] = "self-intersections not checked";
  if (c.intersections_checked) {
    std::snprintf(crossings, sizeof crossings, "%zu self-intersections", c.self_intersections);
  }
  std::snprintf(line, sizeof line,
                "%s, %s: %zu open edges, %zu non-manifold edges, %zu misoriented edges, %zu "
                "degenerate triangles, %s",
                c.closed() ? "closed" : "open", c.manifold() ? "manifold" : "not manifold",
                c.open_edges, c.non_manifold_edges, c.misoriented_edges, c.degenerate_triangles,
                crossings);
  return line;
}

}  // namespace twister::meshio
