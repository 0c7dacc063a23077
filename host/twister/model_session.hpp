// A SculptSession over a model loaded from an OBJ file, for the tools that replay
// journal records (`twister replay`, `twister journal check|salvage --mesh`): the mesh,
// the session's working memory sized from it (refinement included: `spare_vertices`
// more vertices and twice as many more triangles, as the station sizes its mesh), and
// the history sizes the station uses unless told otherwise. open() returns a loading
// error as a value ("PATH: why"; the commands exit 2, bad input).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "twister/hal/expected.hpp"
#include "twister/meshio/obj_file.hpp"
#include "twister/meshio/refiner_buffer.hpp"
#include "twister/meshio/symmetry_buffer.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::cli {

class ModelSession {
 public:
  static hal::Expected<std::unique_ptr<ModelSession>> open(
      const std::string& obj_path, std::size_t spare_vertices = 0,
      std::size_t undo_changes = session::kDefaultUndoChanges,
      std::size_t undo_entries = session::kDefaultUndoEntries);
  ModelSession(const ModelSession&) = delete;
  ModelSession& operator=(const ModelSession&) = delete;

  mesh::Mesh& mesh() { return model_.buffer->mesh(); }
  session::SculptSession& session() { return *session_; }

 private:
  ModelSession(meshio::ObjMesh model, std::size_t undo_changes, std::size_t undo_entries);

  meshio::ObjMesh model_;
  std::vector<float> lx_, ly_, lz_, w1_, w2_;
  std::vector<float> cx_, cy_, cz_;  // a clutch chain's start (ClutchChain)
  meshio::SymmetryBuffer symmetry_;  // as the station's: replays compute as it did
  std::vector<std::uint32_t> plan_indices_;
  std::vector<session::VertexChange> changes_;
  std::vector<session::UndoEntry> entries_;
  meshio::RefinerBuffer refiner_;
  std::vector<session::TriangleChange> triangles_;
  std::unique_ptr<session::SculptSession> session_;
};

}  // namespace twister::cli
