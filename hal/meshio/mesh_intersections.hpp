// Self-intersections of a triangle mesh (private to meshio): pairs of triangles that
// share no vertex and whose interiors cross, found through a uniform grid over the
// bounding box (about as many cells as triangles; each pair is tested once, in the
// cell holding the low corner of their boxes' overlap). Two triangles cross when an
// edge of one passes through the other's interior (Moller-Trumbore in doubles with a
// small relative tolerance, so touching at a point or along an edge is not a
// crossing); coplanar overlaps are not counted.
#pragma once

#include <cstddef>

#include "twister/mesh/mesh.hpp"

namespace twister::meshio::internal {

std::size_t count_self_intersections(const mesh::Mesh& mesh);

}  // namespace twister::meshio::internal
