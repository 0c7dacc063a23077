// Which faces of a mesh can ever be seen from outside it, so the display may skip
// the others (back-face culling, issue 24's frame cost). A mesh whose every edge
// joins exactly two triangles that run along it in opposite directions (closed,
// manifold, consistently oriented: core's TriangleAdjacency) and whose every
// connected piece encloses a positive volume (counter-clockwise seen from outside:
// its faces' normals point out) shows only its front faces to an eye outside it;
// every piece negative (the whole mesh wound clockwise): only its back faces. Any
// other mesh (a grid or an OBJ with holes, an edge of three triangles, a degenerate
// triangle, pieces wound both ways, a flat double-sided sheet) shows both sides,
// and the sculptor must see both. Object frame; the rest mesh, not a warped one.
#pragma once

#include "mesh_data.hpp"

namespace twister::bridge {

enum class Facing : unsigned char {
  both_sides,  // draw both faces (open, non-manifold, inconsistent or mixed winding)
  front,       // closed, every piece counter-clockwise from outside: cull back faces
  back,        // closed, every piece clockwise from outside: cull front faces
};

Facing surface_facing(const MeshData& mesh);

}  // namespace twister::bridge
