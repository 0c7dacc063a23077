#include "surface_facing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "twister/mesh/triangle_adjacency.hpp"

namespace twister::bridge {
namespace {

// Union-find over triangles (the connected pieces).
struct Pieces {
  std::vector<std::uint32_t> parent;
  explicit Pieces(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0U); }
  std::uint32_t find(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
};

}  // namespace

Facing surface_facing(const MeshData& mesh) {
  const std::size_t triangles = mesh.triangle_count();
  if (triangles == 0) return Facing::both_sides;
  const auto core = to_core_mesh(mesh);
  if (!core) return Facing::both_sides;
  std::vector<std::uint32_t> twins(3 * triangles);
  std::vector<std::uint32_t> offsets(mesh.vertex_count() + 1);
  std::vector<std::uint32_t> incident(3 * triangles);
  mesh::TriangleAdjacency adjacency({twins, offsets, incident});
  if (!adjacency.build(core->mesh()).ok()) return Facing::both_sides;
  Pieces pieces(triangles);
  const auto corner = [&mesh](std::uint32_t h) { return mesh.indices[h]; };
  const auto next = [](std::uint32_t h) { return h % 3 == 2 ? h - 2 : h + 1; };
  for (std::uint32_t h = 0; h < 3 * triangles; ++h) {
    const std::uint32_t g = adjacency.twin(h);
    if (g == mesh::kBoundary || g == mesh::kNonManifold) return Facing::both_sides;
    // Consistent winding: the twin runs the other way (b -> a for a -> b).
    if (corner(g) != corner(next(h)) || corner(next(g)) != corner(h)) return Facing::both_sides;
    pieces.join(h / 3, g / 3);
  }
  // Each piece's signed volume (divergence theorem, about its first corner so that
  // far-off coordinates lose no precision) and its extent for the tolerance.
  std::vector<double> volume(triangles, 0.0);
  std::vector<double> extent(triangles, 0.0);
  std::vector<std::uint32_t> origin(triangles, UINT32_MAX);
  const auto at = [&mesh](std::uint32_t v) {
    return std::array<double, 3>{mesh.x[v], mesh.y[v], mesh.z[v]};
  };
  for (std::uint32_t t = 0; t < triangles; ++t) {
    const std::uint32_t p = pieces.find(t);
    if (origin[p] == UINT32_MAX) origin[p] = corner(3 * t);
    const auto o = at(origin[p]);
    std::array<std::array<double, 3>, 3> c{};
    for (std::uint32_t k = 0; k < 3; ++k) {
      const auto v = at(corner(3 * t + k));
      for (std::size_t i = 0; i < 3; ++i) {
        c[k][i] = v[i] - o[i];
        extent[p] = std::max(extent[p], std::abs(c[k][i]));
      }
    }
    const double cross[3] = {c[1][1] * c[2][2] - c[1][2] * c[2][1],
                             c[1][2] * c[2][0] - c[1][0] * c[2][2],
                             c[1][0] * c[2][1] - c[1][1] * c[2][0]};
    volume[p] += (c[0][0] * cross[0] + c[0][1] * cross[1] + c[0][2] * cross[2]) / 6.0;
  }
  bool any_out = false;
  bool any_in = false;
  for (std::uint32_t p = 0; p < triangles; ++p) {
    if (origin[p] == UINT32_MAX) continue;
    // A piece that encloses next to nothing (a double-sided sheet, two triangles
    // back to back) has no inside to hide its back faces.
    const double tolerance = 1e-6 * extent[p] * extent[p] * extent[p];
    if (!(std::abs(volume[p]) > tolerance)) return Facing::both_sides;
    (volume[p] > 0.0 ? any_out : any_in) = true;
  }
  if (any_out && any_in) return Facing::both_sides;
  return any_out ? Facing::front : Facing::back;
}

}  // namespace twister::bridge
