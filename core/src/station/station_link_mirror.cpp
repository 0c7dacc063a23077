// MeshMirror: a commit is one change set (vertices whose bits changed or that are
// new, runs of triangles that changed or are new, the counts after the commit,
// version and checksum), queued all or nothing; anything that does not fit becomes
// a full send from the shadow, a few frames per poll.
#include "twister/station/station_link_mirror.hpp"

#include <algorithm>
#include <bit>

namespace twister::station {
namespace {

bool same_bits(float a, float b) {
  return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

}  // namespace

Status MeshMirror::start(const mesh::Mesh& mesh) {
  TWISTER_TRY(shadow_.copy_from(mesh));
  version_ = 1;
  checksum_ = shadow_.checksum();
  return ok_status();
}

MeshIdentity MeshMirror::offered() {
  if (checksum_stale_) {
    checksum_ = shadow_.checksum();
    checksum_stale_ = false;
  }
  return MeshIdentity{version_, checksum_};
}

void MeshMirror::resync(const MeshIdentity& holds) {
  // Resync by version: a display that holds exactly our mesh gets nothing again.
  if (holds != offered()) full_wanted_ = true;
}

void MeshMirror::track(const mesh::Mesh& mesh, bool send) {
  const auto old_vertices = static_cast<std::uint32_t>(shadow_.vertex_count());
  const auto old_triangles = static_cast<std::uint32_t>(shadow_.triangle_count());
  ++version_;
  checksum_stale_ = true;  // a commit queued for the display computes it now
  const bool sent =
      send && !full_active_ && !full_wanted_ && queue_commit(mesh, old_vertices, old_triangles);
  if (!shadow_.copy_from(mesh).ok()) {
    // Larger than the shadow (cannot happen when sized from the mesh capacity).
    shadow_.clear();
    checksum_stale_ = true;
  }
  if (full_active_) {
    full_phase_ = FullPhase::begin;  // restart from the fresh shadow
    full_next_ = 0;
  } else if (!sent && send) {
    full_wanted_ = true;
  }
}

bool MeshMirror::queue_commit(const mesh::Mesh& mesh, std::uint32_t old_vertices,
                              std::uint32_t old_triangles) {
  const std::size_t mark = out_.bulk_mark();
  bool ok = out_.bulk(link::MeshBegin{false, version_ - 1, version_,
                                      static_cast<std::uint32_t>(mesh.vertex_count()),
                                      static_cast<std::uint32_t>(mesh.triangle_count())}) &&
            queue_changed_vertices(mesh, old_vertices) &&
            queue_changed_triangles(mesh, old_triangles);
  checksum_ = mesh.checksum();  // the shadow's once it is copied from `mesh`
  checksum_stale_ = false;
  ok = ok && out_.bulk(link::MeshEnd{version_, checksum_});
  if (!ok) {
    out_.bulk_rewind(mark);  // all or nothing: never a half commit in the buffer
    return false;
  }
  ++counters_.commits_sent;
  return true;
}

bool MeshMirror::queue_changed_vertices(const mesh::Mesh& mesh, std::uint32_t old_vertices) {
  vertices_.count = 0;
  const auto sx = shadow_.x();
  const auto sy = shadow_.y();
  const auto sz = shadow_.z();
  const auto mx = mesh.x();
  const auto my = mesh.y();
  const auto mz = mesh.z();
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const bool changed = i >= old_vertices || !same_bits(sx[i], mx[i]) ||
                         !same_bits(sy[i], my[i]) || !same_bits(sz[i], mz[i]);
    if (!changed) continue;
    vertices_.items[vertices_.count++] =
        link::VertexEntry{static_cast<std::uint32_t>(i), mx[i], my[i], mz[i]};
    if (vertices_.count == link::kMaxVerticesPerChunk) {
      if (!out_.bulk(vertices_)) return false;
      vertices_.count = 0;
    }
  }
  return vertices_.count == 0 || out_.bulk(vertices_);
}

bool MeshMirror::queue_changed_triangles(const mesh::Mesh& mesh, std::uint32_t old_triangles) {
  // Runs of triangles whose indices changed (edge splits rewrite triangles in place)
  // or that are new; a shorter mesh is cut by the count in mesh_begin.
  const auto old_idx = shadow_.triangle_indices();
  const auto new_idx = mesh.triangle_indices();
  const std::size_t n = mesh.triangle_count();
  const auto changed = [&](std::size_t t) {
    return t >= old_triangles || old_idx[3 * t] != new_idx[3 * t] ||
           old_idx[3 * t + 1] != new_idx[3 * t + 1] || old_idx[3 * t + 2] != new_idx[3 * t + 2];
  };
  std::size_t t = 0;
  while (t < n) {
    if (!changed(t)) {
      ++t;
      continue;
    }
    std::size_t run = 0;
    while (t + run < n && run < link::kMaxTrianglesPerChunk && changed(t + run)) ++run;
    triangles_.first = static_cast<std::uint32_t>(t);
    triangles_.count = static_cast<std::uint16_t>(run);
    std::copy_n(new_idx.begin() + static_cast<std::ptrdiff_t>(3 * t), 3 * run,
                triangles_.indices.begin());
    if (!out_.bulk(triangles_)) return false;
    t += run;
  }
  return true;
}

void MeshMirror::send() {
  if (full_wanted_ && !full_active_) {
    full_wanted_ = false;
    full_active_ = true;
    full_phase_ = FullPhase::begin;
    full_next_ = 0;
    ++counters_.full_sends;
  }
  if (full_active_) continue_full();
}

void MeshMirror::full_vertices() {
  const std::size_t n = std::min(link::kMaxVerticesPerChunk, shadow_.vertex_count() - full_next_);
  vertices_.count = static_cast<std::uint16_t>(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::uint32_t>(full_next_ + k);
    const glm::vec3 p = shadow_.position(i);
    vertices_.items[k] = link::VertexEntry{i, p.x, p.y, p.z};
  }
  if (n > 0) (void)out_.bulk(vertices_);
  full_next_ += n;
  if (full_next_ >= shadow_.vertex_count()) {
    full_phase_ = FullPhase::triangles;
    full_next_ = 0;
  }
}

void MeshMirror::full_triangles() {
  const std::size_t n =
      std::min(link::kMaxTrianglesPerChunk, shadow_.triangle_count() - full_next_);
  triangles_.first = static_cast<std::uint32_t>(full_next_);
  triangles_.count = static_cast<std::uint16_t>(n);
  std::copy_n(shadow_.triangle_indices().begin() + static_cast<std::ptrdiff_t>(3 * full_next_),
              3 * n, triangles_.indices.begin());
  if (n > 0) (void)out_.bulk(triangles_);
  full_next_ += n;
  if (full_next_ >= shadow_.triangle_count()) full_phase_ = FullPhase::end;
}

void MeshMirror::continue_full() {
  // A few frames per poll keep the loop responsive; the rest follows next poll.
  while (full_active_ && out_.bulk_room() >= link::kMaxFrameBytes) {
    switch (full_phase_) {
      case FullPhase::begin:
        (void)out_.bulk(link::MeshBegin{true, 0, version_,
                                        static_cast<std::uint32_t>(shadow_.vertex_count()),
                                        static_cast<std::uint32_t>(shadow_.triangle_count())});
        full_phase_ = FullPhase::vertices;
        full_next_ = 0;
        break;
      case FullPhase::vertices:
        full_vertices();
        break;
      case FullPhase::triangles:
        full_triangles();
        break;
      case FullPhase::end:
        (void)out_.bulk(link::MeshEnd{version_, offered().checksum});
        full_active_ = false;
        break;
    }
  }
}

}  // namespace twister::station
