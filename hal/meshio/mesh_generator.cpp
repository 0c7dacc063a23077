#include "twister/meshio/mesh_generator.hpp"

#include <cmath>
#include <numbers>

namespace twister::meshio {

Status make_grid(mesh::Mesh& mesh, std::size_t n, float half_size_m) {
  mesh.clear();
  if (n < 2 || !std::isfinite(half_size_m)) return StatusCode::invalid_argument;
  if (grid_vertices(n) > mesh.vertex_capacity() || grid_triangles(n) > mesh.triangle_capacity()) {
    return StatusCode::resource_exhausted;
  }
  const float step = 2.0f * half_size_m / static_cast<float>(n - 1);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t i = 0; i < n; ++i) {
      (void)mesh.add_vertex({-half_size_m + step * static_cast<float>(i),
                             -half_size_m + step * static_cast<float>(j), 0.0f});
    }
  }
  for (std::size_t j = 0; j + 1 < n; ++j) {
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const auto a = static_cast<std::uint32_t>(j * n + i);
      const auto nn = static_cast<std::uint32_t>(n);
      (void)mesh.add_triangle(a, a + 1, a + nn);
      (void)mesh.add_triangle(a + 1, a + nn + 1, a + nn);
    }
  }
  return ok_status();
}

Status make_sphere(mesh::Mesh& mesh, std::size_t rings, std::size_t segments, float radius_m) {
  mesh.clear();
  if (rings < 2 || segments < 3 || !std::isfinite(radius_m)) return StatusCode::invalid_argument;
  if (sphere_vertices(rings, segments) > mesh.vertex_capacity() ||
      sphere_triangles(rings, segments) > mesh.triangle_capacity()) {
    return StatusCode::resource_exhausted;
  }
  constexpr double kPi = std::numbers::pi;
  (void)mesh.add_vertex({0.0f, 0.0f, radius_m});  // north pole: 0
  for (std::size_t r = 1; r < rings; ++r) {
    const double theta = kPi * static_cast<double>(r) / static_cast<double>(rings);
    for (std::size_t s = 0; s < segments; ++s) {
      const double phi = 2.0 * kPi * static_cast<double>(s) / static_cast<double>(segments);
      (void)mesh.add_vertex({static_cast<float>(radius_m * std::sin(theta) * std::cos(phi)),
                             static_cast<float>(radius_m * std::sin(theta) * std::sin(phi)),
                             static_cast<float>(radius_m * std::cos(theta))});
    }
  }
  const auto south = static_cast<std::uint32_t>(mesh.vertex_count());
  (void)mesh.add_vertex({0.0f, 0.0f, -radius_m});
  const auto seg = static_cast<std::uint32_t>(segments);
  auto ring_vertex = [seg](std::size_t ring, std::uint32_t s) {
    return static_cast<std::uint32_t>(1 + (ring - 1) * seg + s % seg);
  };
  for (std::uint32_t s = 0; s < seg; ++s) {
    (void)mesh.add_triangle(0, ring_vertex(1, s), ring_vertex(1, s + 1));
    (void)mesh.add_triangle(south, ring_vertex(rings - 1, s + 1), ring_vertex(rings - 1, s));
  }
  for (std::size_t r = 1; r + 1 < rings; ++r) {
    for (std::uint32_t s = 0; s < seg; ++s) {
      const std::uint32_t a = ring_vertex(r, s), b = ring_vertex(r, s + 1);
      const std::uint32_t c = ring_vertex(r + 1, s), d = ring_vertex(r + 1, s + 1);
      (void)mesh.add_triangle(a, c, b);
      (void)mesh.add_triangle(b, c, d);
    }
  }
  return ok_status();
}

}  // namespace twister::meshio
