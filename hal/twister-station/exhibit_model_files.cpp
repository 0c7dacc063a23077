// The archive's model files through hal/meshio's writers (issue 25, export branch):
// binary STL (+Z up, mm, checked closed and manifold first), binary glTF (+Y up,
// metres, a clay material) and a 256-pixel thumbnail PNG, upright from the model's up
// and centred. Their errors carry a message; a full disk is told apart by its text
// (strerror of ENOSPC, EDQUOT, EFBIG) so the station can report it as such.
#include <cerrno>
#include <cstring>
#include <string>

#include "exhibit_archive.hpp"
#include "twister/meshio/mesh_export.hpp"
#include "twister/meshio/thumbnail.hpp"

namespace twister::station_app {
namespace {

int errno_of(const hal::Error& e) {
  for (const int err : {ENOSPC, EDQUOT, EFBIG}) {
    if (e.message.find(std::strerror(err)) != std::string::npos) return err;
  }
  return e.status.code() == StatusCode::failed_precondition ? EEXIST : EIO;
}

class MeshioWriter final : public ArchiveModelWriter {
 public:
  explicit MeshioWriter(glm::vec3 up) { options_.up = up; }
  int write_stl(const std::string& path, const mesh::Mesh& m, const Pose& /*pose*/) override {
    auto r = meshio::write_stl(path, m, options_);
    return r ? 0 : errno_of(r.error());
  }
  int write_glb(const std::string& path, const mesh::Mesh& m, const Pose& /*pose*/) override {
    auto r = meshio::write_glb(path, m, options_);
    return r ? 0 : errno_of(r.error());
  }
  int write_thumbnail(const std::string& path, const mesh::Mesh& m, const Pose& /*pose*/) override {
    auto r = meshio::render_thumbnail_png(m, options_.up, 256, path);
    return r ? 0 : errno_of(r.error());
  }

 private:
  meshio::ExportOptions options_;
};

}  // namespace

std::unique_ptr<ArchiveModelWriter> meshio_model_writer(glm::vec3 up) {
  return std::make_unique<MeshioWriter>(up);
}

}  // namespace twister::station_app
