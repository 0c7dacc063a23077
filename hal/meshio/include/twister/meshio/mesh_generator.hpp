// Procedural meshes for tests and demos (object frame, metres, centred at 0).
#pragma once

#include <cstddef>

#include "twister/base/status.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::meshio {

// n x n vertices over [-half, half]^2 at z = 0, two triangles per cell (n >= 2).
// resource_exhausted: does not fit (mesh left cleared); invalid_argument: n < 2 or a
// size that is not finite (both generators).
Status make_grid(mesh::Mesh& mesh, std::size_t n, float half_size_m);
inline constexpr std::size_t grid_vertices(std::size_t n) { return n * n; }
inline constexpr std::size_t grid_triangles(std::size_t n) { return 2 * (n - 1) * (n - 1); }

// UV sphere: `rings` >= 2 latitude bands, `segments` >= 3 longitudes, poles shared.
Status make_sphere(mesh::Mesh& mesh, std::size_t rings, std::size_t segments, float radius_m);
inline constexpr std::size_t sphere_vertices(std::size_t rings, std::size_t segments) {
  return (rings - 1) * segments + 2;
}
inline constexpr std::size_t sphere_triangles(std::size_t rings, std::size_t segments) {
  return 2 * (rings - 1) * segments;
}

// Closed box [-half, half]^3: every face an n x n grid of vertices (n >= 2 per edge,
// shared along the box's edges and corners), two triangles per cell, outward
// (counter-clockwise seen from outside). The paper's Figure 6 twists a box.
Status make_box(mesh::Mesh& mesh, std::size_t n, float half_size_m);
inline constexpr std::size_t box_vertices(std::size_t n) { return 6 * n * n - 12 * n + 8; }
inline constexpr std::size_t box_triangles(std::size_t n) { return 12 * (n - 1) * (n - 1); }

// Closed cylinder about z, radius r, z in [-half_height, half_height]: `rings` >= 1
// bands of quads along the height, `segments` >= 3 around, each cap a fan around a
// centre vertex; outward.
Status make_cylinder(mesh::Mesh& mesh, std::size_t rings, std::size_t segments, float radius_m,
                     float half_height_m);
inline constexpr std::size_t cylinder_vertices(std::size_t rings, std::size_t segments) {
  return (rings + 1) * segments + 2;
}
inline constexpr std::size_t cylinder_triangles(std::size_t rings, std::size_t segments) {
  return 2 * rings * segments + 2 * segments;
}

}  // namespace twister::meshio
