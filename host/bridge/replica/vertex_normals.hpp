// Smooth-shading normals of a MeshData: per vertex, the area-weighted sum of the
// normals of the triangles around it (counter-clockwise winding), normalised.
// A vertex in no triangle (or only in degenerate ones) gets (0, 0, 1). Object
// frame; 3 floats per vertex (x y z ...), `out` resized to 3 * vertex_count.
#pragma once

#include <vector>

#include "scene_replica.hpp"

namespace twister::bridge {

void compute_vertex_normals(const MeshData& mesh, std::vector<float>& out);

}  // namespace twister::bridge
