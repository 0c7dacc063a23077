// LiveMesh: the model a session sculpts, as two sets of columns over the same
// vertices. rest() is the mesh (object frame), changed only by commits and undo/redo;
// live() holds the warped positions of the open stroke, written by the warp plan
// (only where the plan has influenced vertices) when a consumer asks for them
// (StrokeController::live_positions(); never per tracker record) and at commit, just
// before they are copied into the mesh. Both views are sized to the mesh's current vertex count.
// Memory: the mesh and the live spans are the caller's and must outlive this object.
#pragma once

#include <span>

#include "twister/math/vertex_columns.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::session {

class LiveMesh {
 public:
  // Each live span must hold at least the mesh's vertex capacity (asserted).
  LiveMesh(mesh::Mesh& mesh, std::span<float> live_x, std::span<float> live_y,
           std::span<float> live_z);
  LiveMesh(const LiveMesh&) = delete;
  LiveMesh& operator=(const LiveMesh&) = delete;

  mesh::Mesh& mesh() { return mesh_; }
  const mesh::Mesh& mesh() const { return mesh_; }
  math::ConstVertexColumns rest() const;
  math::VertexColumns live();
  math::ConstVertexColumns live() const;

 private:
  mesh::Mesh& mesh_;
  std::span<float> live_x_;
  std::span<float> live_y_;
  std::span<float> live_z_;
};

}  // namespace twister::session
