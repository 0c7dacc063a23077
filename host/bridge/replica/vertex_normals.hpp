// Smooth-shading normals of a MeshData: core's mesh::compute_vertex_normals (the
// station's own: area-weighted, counter-clockwise outward; (0, 0, 0) for a vertex
// on no triangle of non-zero area), interleaved for the display: 3 floats per
// vertex (x y z ...), `out` resized to 3 * vertex_count. Object frame.
#pragma once

#include <vector>

#include "scene_replica.hpp"

namespace twister::bridge {

void compute_vertex_normals(const MeshData& mesh, std::vector<float>& out);

}  // namespace twister::bridge
