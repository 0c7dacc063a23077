// Vertex normals of a Mesh: area-weighted (each triangle adds its cross product,
// twice its area along its normal, to its three vertices), then normalised; a
// vertex on no triangle of non-zero area gets (0, 0, 0). Counter-clockwise
// triangles give outward normals. O(triangles + vertices), no allocation; the
// station recomputes them after every change of the model, and a display can call
// the same function on its replica.
#pragma once

#include <span>

#include "twister/base/status.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::mesh {

struct NormalColumns {
  std::span<float> x;
  std::span<float> y;
  std::span<float> z;
};

// Writes the normal of every vertex into out[0, vertex_count()).
// invalid_argument: a column is shorter than mesh.vertex_count().
Status compute_vertex_normals(const Mesh& mesh, NormalColumns out);

}  // namespace twister::mesh
