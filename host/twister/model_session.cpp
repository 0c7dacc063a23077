#include "model_session.hpp"

#include <algorithm>

#include "cli_exit.hpp"
#include "cli_log.hpp"

namespace twister::cli {
namespace {

meshio::ObjMesh load(const std::string& path, std::size_t spare_vertices) {
  meshio::ObjOptions options;
  options.spare_vertices = spare_vertices;
  options.spare_triangles = 2 * spare_vertices;
  auto loaded = meshio::load_obj(path, options);
  if (!loaded) {
    cli_log().error("", "%s: %s", path.c_str(), loaded.error().message.c_str());
    throw Exit{kExitBadInput};
  }
  if (loaded->skipped_lines > 0) {
    cli_log().warning("", "%s: %zu unsupported lines skipped", path.c_str(), loaded->skipped_lines);
  }
  return std::move(*loaded);
}

}  // namespace

ModelSession::ModelSession(const std::string& obj_path, std::size_t spare_vertices,
                           std::size_t undo_changes, std::size_t undo_entries)
    : model_(load(obj_path, spare_vertices)),
      refiner_(mesh().vertex_capacity(), mesh().triangle_capacity()),
      triangles_(session::kDefaultUndoTriangleChanges) {
  const std::size_t n = mesh().vertex_capacity();
  for (auto* v : {&lx_, &ly_, &lz_, &w1_, &w2_}) v->resize(n);
  plan_indices_.resize(n);
  changes_.resize(undo_changes);
  entries_.resize(std::max<std::size_t>(undo_entries, 1));
  const session::SculptStorage work{lx_,
                                  ly_,
                                  lz_,
                                  math::WarpPlanStorage{plan_indices_, w1_, w2_},
                                  changes_,
                                  entries_,
                                  refiner_.storage(),
                                  triangles_};
  session_ =
      std::make_unique<session::SculptSession>(session::SculptSessionConfig{}, mesh(), work, nullptr);
}

}  // namespace twister::cli
