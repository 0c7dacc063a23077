#include "model_session.hpp"

#include <algorithm>

#include "cli_log.hpp"

namespace twister::cli {

hal::Expected<std::unique_ptr<ModelSession>> ModelSession::open(const std::string& obj_path,
                                                                std::size_t spare_vertices,
                                                                std::size_t undo_changes,
                                                                std::size_t undo_entries) {
  meshio::ObjOptions options;
  options.spare_vertices = spare_vertices;
  options.spare_triangles = 2 * spare_vertices;
  auto loaded = meshio::load_obj(obj_path, options);
  if (!loaded) {
    return hal::Error{loaded.error().status, obj_path + ": " + loaded.error().message};
  }
  if (loaded->skipped_lines > 0) {
    cli_log().warning("", "%s: %zu unsupported lines skipped", obj_path.c_str(),
                      loaded->skipped_lines);
  }
  return std::unique_ptr<ModelSession>(
      new ModelSession(std::move(*loaded), undo_changes, undo_entries));
}

ModelSession::ModelSession(meshio::ObjMesh model, std::size_t undo_changes,
                           std::size_t undo_entries)
    : model_(std::move(model)),
      symmetry_(mesh().vertex_capacity()),
      refiner_(mesh().vertex_capacity(), mesh().triangle_capacity()),
      triangles_(session::kDefaultUndoTriangleChanges) {
  const std::size_t n = mesh().vertex_capacity();
  for (auto* v : {&lx_, &ly_, &lz_, &w1_, &w2_, &cx_, &cy_, &cz_}) v->resize(n);
  plan_indices_.resize(n);
  changes_.resize(undo_changes);
  entries_.resize(std::max<std::size_t>(undo_entries, 1));
  session::SculptStorage work{
      lx_,
      ly_,
      lz_,
      math::WarpPlanStorage{plan_indices_, w1_, w2_, symmetry_.plan_symmetry()},
      changes_,
      entries_,
      refiner_.storage(),
      triangles_};
  work.chain_start = math::VertexColumns{cx_, cy_, cz_};  // refined clutch chains replay
  session_ = std::make_unique<session::SculptSession>(session::SculptSessionConfig{}, mesh(), work,
                                                      nullptr);
}

}  // namespace twister::cli
