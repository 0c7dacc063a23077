#include "mesh_intersections.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <vector>

namespace twister::meshio::internal {
namespace {

using Tri = std::array<glm::dvec3, 3>;

struct Box {
  glm::dvec3 lo{1e300};
  glm::dvec3 hi{-1e300};
};

constexpr double kTolerance = 1e-9;  // of the barycentric and segment parameters

// Does segment p0 -> p1 pass through the interior of triangle t?
bool segment_crosses(glm::dvec3 p0, glm::dvec3 p1, const Tri& t) {
  const glm::dvec3 e1 = t[1] - t[0];
  const glm::dvec3 e2 = t[2] - t[0];
  const glm::dvec3 d = p1 - p0;
  const glm::dvec3 pvec = glm::cross(d, e2);
  const double det = glm::dot(e1, pvec);
  const double scale = glm::length(d) * glm::length(e1) * glm::length(e2);
  if (std::abs(det) <= 1e-12 * scale) return false;  // parallel (or coplanar)
  const double inv = 1.0 / det;
  const glm::dvec3 tvec = p0 - t[0];
  const double u = glm::dot(tvec, pvec) * inv;
  if (u < kTolerance || u > 1.0 - kTolerance) return false;
  const glm::dvec3 qvec = glm::cross(tvec, e1);
  const double v = glm::dot(d, qvec) * inv;
  if (v < kTolerance || u + v > 1.0 - kTolerance) return false;
  const double s = glm::dot(e2, qvec) * inv;
  return s > kTolerance && s < 1.0 - kTolerance;
}

bool triangles_cross(const Tri& a, const Tri& b) {
  for (std::size_t k = 0; k < 3; ++k) {
    if (segment_crosses(a[k], a[(k + 1) % 3], b)) return true;
    if (segment_crosses(b[k], b[(k + 1) % 3], a)) return true;
  }
  return false;
}

bool share_vertex(const std::array<std::uint32_t, 3>& a, const std::array<std::uint32_t, 3>& b) {
  for (const std::uint32_t x : a) {
    if (x == b[0] || x == b[1] || x == b[2]) return true;
  }
  return false;
}

// The uniform grid: cell size and counts per axis.
struct Grid {
  glm::dvec3 origin{0.0};
  double cell = 1.0;
  std::array<std::size_t, 3> n{1, 1, 1};

  std::size_t axis_cell(double v, int axis) const {
    const double c = std::floor((v - origin[axis]) / cell);
    if (c <= 0.0) return 0;
    return std::min(static_cast<std::size_t>(c), n[static_cast<std::size_t>(axis)] - 1);
  }
  std::size_t index(std::size_t i, std::size_t j, std::size_t k) const {
    return (k * n[1] + j) * n[0] + i;
  }
};

Grid make_grid(const Box& all, std::size_t triangles) {
  Grid g;
  g.origin = all.lo;
  const glm::dvec3 span = all.hi - all.lo;
  const double largest = std::max({span.x, span.y, span.z, 1e-12});
  // A flat mesh's thin axis counts as a thousandth of the largest (one cell thick).
  const glm::dvec3 extent = glm::max(span, glm::dvec3(1e-3 * largest));
  const double volume = extent.x * extent.y * extent.z;
  g.cell = std::cbrt(volume / static_cast<double>(std::max<std::size_t>(triangles, 1)));
  g.cell = std::max(g.cell, largest / 256.0);
  for (int a = 0; a < 3; ++a) {
    g.n[static_cast<std::size_t>(a)] =
        static_cast<std::size_t>(std::max(1.0, std::ceil(extent[a] / g.cell)));
  }
  return g;
}

}  // namespace

std::size_t count_self_intersections(const mesh::Mesh& mesh) {
  const std::size_t count = mesh.triangle_count();
  if (count < 2) return 0;
  std::vector<Box> boxes(count);
  Box all;
  for (std::uint32_t t = 0; t < count; ++t) {
    for (const std::uint32_t v : mesh.triangle(t)) {
      const glm::dvec3 p(mesh.position(v));
      boxes[t].lo = glm::min(boxes[t].lo, p);
      boxes[t].hi = glm::max(boxes[t].hi, p);
    }
    all.lo = glm::min(all.lo, boxes[t].lo);
    all.hi = glm::max(all.hi, boxes[t].hi);
  }
  const Grid grid = make_grid(all, count);
  const std::size_t cells = grid.n[0] * grid.n[1] * grid.n[2];
  // Two passes (count, fill): each cell's triangles contiguous in `members`.
  std::vector<std::size_t> start(cells + 1, 0);
  std::vector<std::uint32_t> members;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::size_t> fill;
    if (pass == 1) {
      for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
      members.resize(start[cells]);
      fill.assign(start.begin(), start.end() - 1);
    }
    for (std::uint32_t t = 0; t < count; ++t) {
      const Box& b = boxes[t];
      for (std::size_t k = grid.axis_cell(b.lo.z, 2); k <= grid.axis_cell(b.hi.z, 2); ++k)
        for (std::size_t j = grid.axis_cell(b.lo.y, 1); j <= grid.axis_cell(b.hi.y, 1); ++j)
          for (std::size_t i = grid.axis_cell(b.lo.x, 0); i <= grid.axis_cell(b.hi.x, 0); ++i) {
            const std::size_t c = grid.index(i, j, k);
            if (pass == 0) {
              ++start[c + 1];
            } else {
              members[fill[c]++] = t;
            }
          }
    }
  }
  std::size_t crossings = 0;
  for (std::size_t k = 0; k < grid.n[2]; ++k)
    for (std::size_t j = 0; j < grid.n[1]; ++j)
      for (std::size_t i = 0; i < grid.n[0]; ++i) {
        const std::size_t c = grid.index(i, j, k);
        for (std::size_t x = start[c]; x < start[c + 1]; ++x) {
          const std::uint32_t ta = members[x];
          const auto va = mesh.triangle(ta);
          for (std::size_t y = x + 1; y < start[c + 1]; ++y) {
            const std::uint32_t tb = members[y];
            const auto vb = mesh.triangle(tb);
            const glm::dvec3 lo = glm::max(boxes[ta].lo, boxes[tb].lo);
            const glm::dvec3 hi = glm::min(boxes[ta].hi, boxes[tb].hi);
            if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) continue;
            // Test each pair once: in the cell of its overlap's low corner.
            if (grid.axis_cell(lo.x, 0) != i || grid.axis_cell(lo.y, 1) != j ||
                grid.axis_cell(lo.z, 2) != k) {
              continue;
            }
            if (share_vertex(va, vb)) continue;
            const Tri a{glm::dvec3(mesh.position(va[0])), glm::dvec3(mesh.position(va[1])),
                        glm::dvec3(mesh.position(va[2]))};
            const Tri b{glm::dvec3(mesh.position(vb[0])), glm::dvec3(mesh.position(vb[1])),
                        glm::dvec3(mesh.position(vb[2]))};
            if (triangles_cross(a, b)) ++crossings;
          }
        }
      }
  return crossings;
}

}  // namespace twister::meshio::internal
