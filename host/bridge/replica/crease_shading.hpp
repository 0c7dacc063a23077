// Crease-aware shading of a MeshData: smooth normals across gentle edges, separate
// normals on the two sides of a sharp one. Two triangles around a vertex share its
// normal when they are joined, through triangles around that vertex, by edges whose
// dihedral angle (between the faces' normals) is at most the crease angle; each such
// group of a vertex's fan becomes one drawn vertex (a box corner becomes three, a
// vertex inside a face or on a smooth surface stays one). A group's normal is the
// area-weighted sum of its faces' normals (core's mesh::compute_vertex_normals on a
// mesh without creases), so a mesh with none draws as before. Object frame.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh_data.hpp"
#include "surface_facing.hpp"

namespace twister::bridge {

// The dihedral angle above which an edge is a crease (degrees; 180: none is).
inline constexpr float kDefaultCreaseAngleDeg = 45.0F;

struct ShadedMesh {
  std::vector<std::uint32_t> source;   // drawn vertex -> mesh vertex
  std::vector<std::uint32_t> indices;  // 3 per triangle, drawn vertices (same order)
  std::vector<float> normals;          // 3 per drawn vertex (unit; 0 on degenerate fans)
  std::size_t vertex_count() const { return source.size(); }
  // Drawn vertices are the mesh's own (no crease split anything).
  bool identity() const { return source.size() == mesh_vertices; }
  std::size_t mesh_vertices = 0;
  // The faces an eye outside the mesh can see (surface_facing.hpp): the renderer
  // culls the others.
  Facing facing = Facing::both_sides;
};

// Groups `mesh`'s fans at `crease_angle_deg` and computes the groups' normals.
ShadedMesh shade_with_creases(const MeshData& mesh, float crease_angle_deg);

// The normals of `shaded`'s groups for other positions of the same mesh (a CPU-warped
// preview): the grouping is kept, only the faces' normals change.
void shade_normals(const MeshData& positions, ShadedMesh& shaded);

// Per drawn vertex, `columns` floats of `per_vertex` (per mesh vertex); missing
// entries (a short input) are zero.
std::vector<float> to_drawn(const ShadedMesh& shaded, const std::vector<float>& per_vertex,
                            std::size_t columns);

}  // namespace twister::bridge
