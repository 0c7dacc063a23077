// The box and cylinder generators (grid and sphere: mesh_generator.cpp).
#include <array>
#include <cmath>
#include <numbers>

#include "twister/meshio/mesh_generator.hpp"

namespace twister::meshio {
namespace {

using Lattice = std::array<std::size_t, 3>;  // (i, j, k): x, y, z steps

// Index of a surface point of the n^3 lattice, in the order the points are added
// (z layers; the bottom and top layers full, the others a ring of 4 (n - 1)).
std::uint32_t box_index(std::size_t n, const Lattice& p) {
  const std::size_t i = p[0], j = p[1], k = p[2];
  const std::size_t ring = 4 * (n - 1);
  std::size_t before = k == 0 ? 0 : n * n + (k - 1) * ring;
  if (k == 0 || k == n - 1) return static_cast<std::uint32_t>(before + j * n + i);
  if (j == 0) return static_cast<std::uint32_t>(before + i);
  if (j == n - 1) return static_cast<std::uint32_t>(before + n + 2 * (n - 2) + i);
  return static_cast<std::uint32_t>(before + n + 2 * (j - 1) + (i == 0 ? 0 : 1));
}

bool on_surface(std::size_t n, std::size_t i, std::size_t j, std::size_t k) {
  return i == 0 || j == 0 || k == 0 || i == n - 1 || j == n - 1 || k == n - 1;
}

// A face: the fixed axis and its lattice value, and the axes u, v with u x v outward.
struct Face {
  std::size_t fixed;
  bool high;
  std::size_t u;
  std::size_t v;
};
constexpr std::array<Face, 6> kFaces{{{0, true, 1, 2},
                                      {0, false, 2, 1},
                                      {1, true, 2, 0},
                                      {1, false, 0, 2},
                                      {2, true, 0, 1},
                                      {2, false, 1, 0}}};

void add_face(mesh::Mesh& mesh, std::size_t n, const Face& f) {
  const auto at = [&](std::size_t a, std::size_t b) {
    Lattice p{};
    p[f.fixed] = f.high ? n - 1 : 0;
    p[f.u] = a;
    p[f.v] = b;
    return box_index(n, p);
  };
  for (std::size_t b = 0; b + 1 < n; ++b) {
    for (std::size_t a = 0; a + 1 < n; ++a) {
      (void)mesh.add_triangle(at(a, b), at(a + 1, b), at(a + 1, b + 1));
      (void)mesh.add_triangle(at(a, b), at(a + 1, b + 1), at(a, b + 1));
    }
  }
}

}  // namespace

Status make_box(mesh::Mesh& mesh, std::size_t n, float half_size_m) {
  mesh.clear();
  if (n < 2 || !std::isfinite(half_size_m)) return StatusCode::invalid_argument;
  if (box_vertices(n) > mesh.vertex_capacity() || box_triangles(n) > mesh.triangle_capacity()) {
    return StatusCode::resource_exhausted;
  }
  const auto coordinate = [&](std::size_t s) {
    if (s == n - 1) return half_size_m;  // the far faces exactly at +half
    return -half_size_m + 2.0f * half_size_m * static_cast<float>(s) / static_cast<float>(n - 1);
  };
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t i = 0; i < n; ++i) {
        if (on_surface(n, i, j, k)) {
          (void)mesh.add_vertex({coordinate(i), coordinate(j), coordinate(k)});
        }
      }
    }
  }
  for (const Face& f : kFaces) add_face(mesh, n, f);
  return ok_status();
}

Status make_cylinder(mesh::Mesh& mesh, std::size_t rings, std::size_t segments, float radius_m,
                     float half_height_m) {
  mesh.clear();
  if (rings < 1 || segments < 3 || !std::isfinite(radius_m) || !std::isfinite(half_height_m)) {
    return StatusCode::invalid_argument;
  }
  if (cylinder_vertices(rings, segments) > mesh.vertex_capacity() ||
      cylinder_triangles(rings, segments) > mesh.triangle_capacity()) {
    return StatusCode::resource_exhausted;
  }
  for (std::size_t r = 0; r <= rings; ++r) {
    const double z =
        -half_height_m + 2.0 * half_height_m * static_cast<double>(r) / static_cast<double>(rings);
    for (std::size_t s = 0; s < segments; ++s) {
      const double phi =
          2.0 * std::numbers::pi * static_cast<double>(s) / static_cast<double>(segments);
      (void)mesh.add_vertex({static_cast<float>(radius_m * std::cos(phi)),
                             static_cast<float>(radius_m * std::sin(phi)), static_cast<float>(z)});
    }
  }
  const auto bottom = static_cast<std::uint32_t>(mesh.vertex_count());
  (void)mesh.add_vertex({0.0f, 0.0f, -half_height_m});
  (void)mesh.add_vertex({0.0f, 0.0f, half_height_m});
  const auto seg = static_cast<std::uint32_t>(segments);
  const auto at = [seg](std::size_t r, std::uint32_t s) {
    return static_cast<std::uint32_t>(r * seg + s % seg);
  };
  for (std::size_t r = 0; r < rings; ++r) {
    for (std::uint32_t s = 0; s < seg; ++s) {
      (void)mesh.add_triangle(at(r, s), at(r, s + 1), at(r + 1, s + 1));
      (void)mesh.add_triangle(at(r, s), at(r + 1, s + 1), at(r + 1, s));
    }
  }
  for (std::uint32_t s = 0; s < seg; ++s) {
    (void)mesh.add_triangle(bottom, at(0, s + 1), at(0, s));
    (void)mesh.add_triangle(bottom + 1, at(rings, s), at(rings, s + 1));
  }
  return ok_status();
}

}  // namespace twister::meshio
