#include "crease_shading.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec3.hpp>
#include <numeric>
#include <utility>

namespace twister::bridge {
namespace {

glm::vec3 position(const MeshData& m, std::uint32_t v) { return {m.x[v], m.y[v], m.z[v]}; }

// Area-weighted normal of triangle t (the cross product of two edges).
glm::vec3 face_normal(const MeshData& m, std::size_t t) {
  const std::uint32_t* i = &m.indices[3 * t];
  const glm::vec3 a = position(m, i[0]);
  return glm::cross(position(m, i[1]) - a, position(m, i[2]) - a);
}

// Union-find over one vertex's fan (local indices).
struct Groups {
  std::vector<std::uint32_t> parent;
  void reset(std::size_t n) {
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), 0U);
  }
  std::uint32_t find(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
};

// Triangle corners around each vertex (compressed rows: corners of vertex v are
// [first[v], first[v + 1]) in `corner`, each 3 * triangle + corner).
struct Fans {
  std::vector<std::uint32_t> first;
  std::vector<std::uint32_t> corner;
  explicit Fans(const MeshData& m) : first(m.vertex_count() + 1, 0), corner(m.indices.size()) {
    for (const std::uint32_t v : m.indices) ++first[v + 1];
    std::partial_sum(first.begin(), first.end(), first.begin());
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (std::size_t c = 0; c < m.indices.size(); ++c) {
      corner[fill[m.indices[c]]++] = static_cast<std::uint32_t>(c);
    }
  }
};

}  // namespace

ShadedMesh shade_with_creases(const MeshData& mesh, float crease_angle_deg) {
  ShadedMesh out;
  const std::size_t n = mesh.vertex_count();
  const std::size_t triangles = mesh.triangle_count();
  out.mesh_vertices = n;
  out.source.resize(n);
  std::iota(out.source.begin(), out.source.end(), 0U);
  out.indices = mesh.indices;
  std::vector<glm::vec3> unit(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    const glm::vec3 f = face_normal(mesh, t);
    const float length = glm::length(f);
    unit[t] = length > 0.0F && std::isfinite(length) ? f / length : glm::vec3(0.0F);
  }
  const float min_cos = std::cos(glm::radians(std::clamp(crease_angle_deg, 0.0F, 180.0F)));
  const Fans fans(mesh);
  Groups groups;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> by_neighbour;  // (other vertex, local)
  std::vector<std::uint32_t> drawn;                                   // per group root
  for (std::uint32_t v = 0; v < n; ++v) {
    const std::uint32_t begin = fans.first[v];
    const std::uint32_t count = fans.first[v + 1] - begin;
    if (count < 2) continue;
    groups.reset(count);
    by_neighbour.clear();
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t c = fans.corner[begin + k];
      const std::uint32_t t = c / 3;
      by_neighbour.emplace_back(mesh.indices[3 * t + (c + 1) % 3], k);
      by_neighbour.emplace_back(mesh.indices[3 * t + (c + 2) % 3], k);
    }
    std::sort(by_neighbour.begin(), by_neighbour.end());
    // Consecutive entries with the same other vertex share the edge (v, other).
    for (std::size_t e = 1; e < by_neighbour.size(); ++e) {
      if (by_neighbour[e].first != by_neighbour[e - 1].first) continue;
      const std::uint32_t a = by_neighbour[e - 1].second;
      const std::uint32_t b = by_neighbour[e].second;
      const glm::vec3 ua = unit[fans.corner[begin + a] / 3];
      const glm::vec3 ub = unit[fans.corner[begin + b] / 3];
      const bool degenerate = glm::dot(ua, ua) == 0.0F || glm::dot(ub, ub) == 0.0F;
      if (degenerate || glm::dot(ua, ub) >= min_cos) groups.join(a, b);
    }
    // The first group keeps the vertex's own index; others are appended.
    drawn.assign(count, UINT32_MAX);
    bool first_group = true;
    for (std::uint32_t k = 0; k < count; ++k) {
      const std::uint32_t root = groups.find(k);
      if (drawn[root] == UINT32_MAX) {
        drawn[root] = first_group ? v : static_cast<std::uint32_t>(out.source.size());
        if (!first_group) out.source.push_back(v);
        first_group = false;
      }
      out.indices[fans.corner[begin + k]] = drawn[root];
    }
  }
  shade_normals(mesh, out);
  out.facing = surface_facing(mesh);
  return out;
}

void shade_normals(const MeshData& positions, ShadedMesh& shaded) {
  const std::size_t drawn = shaded.vertex_count();
  std::vector<glm::vec3> sum(drawn, glm::vec3(0.0F));
  for (std::size_t t = 0; t < positions.triangle_count(); ++t) {
    const glm::vec3 f = face_normal(positions, t);
    for (std::size_t c = 0; c < 3; ++c) sum[shaded.indices[3 * t + c]] += f;
  }
  shaded.normals.assign(3 * drawn, 0.0F);
  for (std::size_t i = 0; i < drawn; ++i) {
    const float length = glm::length(sum[i]);
    if (!(length > 0.0F) || !std::isfinite(length)) continue;
    for (glm::length_t k = 0; k < 3; ++k) {
      shaded.normals[3 * i + static_cast<std::size_t>(k)] = sum[i][k] / length;
    }
  }
}

std::vector<float> to_drawn(const ShadedMesh& shaded, const std::vector<float>& per_vertex,
                            std::size_t columns) {
  std::vector<float> out(columns * shaded.vertex_count(), 0.0F);
  for (std::size_t i = 0; i < shaded.vertex_count(); ++i) {
    const std::size_t from = columns * shaded.source[i];
    if (from + columns > per_vertex.size()) continue;
    std::copy_n(per_vertex.begin() + static_cast<std::ptrdiff_t>(from), columns,
                out.begin() + static_cast<std::ptrdiff_t>(columns * i));
  }
  return out;
}

}  // namespace twister::bridge
