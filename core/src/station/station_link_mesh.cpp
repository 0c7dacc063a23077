// StationLink: the committed mesh. A commit is one change set (vertices whose bits
// changed or that are new, runs of triangles that changed or are new, the counts
// after the commit, version and checksum), queued all or nothing; anything that
// does not fit becomes a full send from the shadow, a few frames per poll.
#include <algorithm>
#include <bit>

#include "twister/station/station_link.hpp"

namespace twister::station {
namespace {

bool same_bits(float a, float b) {
  return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

}  // namespace

void StationLink::track_mesh(const mesh::Mesh& mesh) {
  const auto old_vertices = static_cast<std::uint32_t>(shadow_.vertex_count());
  const auto old_triangles = static_cast<std::uint32_t>(shadow_.triangle_count());
  ++version_;
  const bool sent = admitted() && !full_active_ && !full_wanted_ &&
                    queue_commit(mesh, old_vertices, old_triangles);
  if (!shadow_.copy_from(mesh).ok()) {
    // Larger than the shadow (cannot happen when sized from the mesh capacity).
    shadow_.clear();
  }
  if (full_active_) {
    full_phase_ = FullPhase::begin;  // restart from the fresh shadow
    full_next_ = 0;
  } else if (!sent && admitted()) {
    full_wanted_ = true;
  }
}

bool StationLink::queue_commit(const mesh::Mesh& mesh, std::uint32_t old_vertices,
                               std::uint32_t old_triangles) {
  const std::size_t saved = out_size_;
  scratch_.type = link::MessageType::mesh_begin;
  scratch_.mesh_begin = link::MeshBegin{false, version_ - 1, version_,
                                        static_cast<std::uint32_t>(mesh.vertex_count()),
                                        static_cast<std::uint32_t>(mesh.triangle_count())};
  bool ok = queue(scratch_) && queue_changed_vertices(mesh, old_vertices) &&
            queue_changed_triangles(mesh, old_triangles);
  if (ok) {
    scratch_.type = link::MessageType::mesh_end;
    scratch_.mesh_end = link::MeshEnd{version_, mesh.checksum()};
    ok = queue(scratch_);
  }
  if (!ok) {
    out_size_ = saved;  // all or nothing: never a half commit in the buffer
    return false;
  }
  ++counters_.commits_sent;
  return true;
}

bool StationLink::queue_changed_vertices(const mesh::Mesh& mesh, std::uint32_t old_vertices) {
  scratch_.type = link::MessageType::vertices;
  scratch_.vertices.count = 0;
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
    scratch_.vertices.items[scratch_.vertices.count++] =
        link::VertexEntry{static_cast<std::uint32_t>(i), mx[i], my[i], mz[i]};
    if (scratch_.vertices.count == link::kMaxVerticesPerChunk) {
      if (!queue(scratch_)) return false;
      scratch_.vertices.count = 0;
    }
  }
  return scratch_.vertices.count == 0 || queue(scratch_);
}

bool StationLink::queue_changed_triangles(const mesh::Mesh& mesh, std::uint32_t old_triangles) {
  // Runs of triangles whose indices changed (edge splits rewrite triangles in place)
  // or that are new; a shorter mesh is cut by the count in mesh_begin.
  const auto old_idx = shadow_.triangle_indices();
  const auto new_idx = mesh.triangle_indices();
  const std::size_t n = mesh.triangle_count();
  const auto changed = [&](std::size_t t) {
    return t >= old_triangles || old_idx[3 * t] != new_idx[3 * t] ||
           old_idx[3 * t + 1] != new_idx[3 * t + 1] || old_idx[3 * t + 2] != new_idx[3 * t + 2];
  };
  scratch_.type = link::MessageType::triangles;
  std::size_t t = 0;
  while (t < n) {
    if (!changed(t)) {
      ++t;
      continue;
    }
    std::size_t run = 0;
    while (t + run < n && run < link::kMaxTrianglesPerChunk && changed(t + run)) ++run;
    scratch_.triangles.first = static_cast<std::uint32_t>(t);
    scratch_.triangles.count = static_cast<std::uint16_t>(run);
    std::copy_n(new_idx.begin() + static_cast<std::ptrdiff_t>(3 * t), 3 * run,
                scratch_.triangles.indices.begin());
    if (!queue(scratch_)) return false;
    t += run;
  }
  return true;
}

void StationLink::start_full() {
  full_wanted_ = false;
  full_active_ = true;
  full_phase_ = FullPhase::begin;
  full_next_ = 0;
  ++counters_.full_sends;
}

void StationLink::continue_full() {
  // A few frames per poll keep the loop responsive; the rest follows next poll.
  while (full_active_ && room() >= link::kMaxFrameBytes) {
    switch (full_phase_) {
      case FullPhase::begin:
        scratch_.type = link::MessageType::mesh_begin;
        scratch_.mesh_begin =
            link::MeshBegin{true, 0, version_, static_cast<std::uint32_t>(shadow_.vertex_count()),
                            static_cast<std::uint32_t>(shadow_.triangle_count())};
        queue(scratch_);
        full_phase_ = FullPhase::vertices;
        full_next_ = 0;
        break;
      case FullPhase::vertices: {
        const std::size_t n =
            std::min(link::kMaxVerticesPerChunk, shadow_.vertex_count() - full_next_);
        scratch_.type = link::MessageType::vertices;
        scratch_.vertices.count = static_cast<std::uint16_t>(n);
        for (std::size_t k = 0; k < n; ++k) {
          const auto i = static_cast<std::uint32_t>(full_next_ + k);
          const glm::vec3 p = shadow_.position(i);
          scratch_.vertices.items[k] = link::VertexEntry{i, p.x, p.y, p.z};
        }
        if (n > 0) queue(scratch_);
        full_next_ += n;
        if (full_next_ >= shadow_.vertex_count()) {
          full_phase_ = FullPhase::triangles;
          full_next_ = 0;
        }
        break;
      }
      case FullPhase::triangles: {
        const std::size_t n =
            std::min(link::kMaxTrianglesPerChunk, shadow_.triangle_count() - full_next_);
        scratch_.type = link::MessageType::triangles;
        scratch_.triangles.first = static_cast<std::uint32_t>(full_next_);
        scratch_.triangles.count = static_cast<std::uint16_t>(n);
        std::copy_n(
            shadow_.triangle_indices().begin() + static_cast<std::ptrdiff_t>(3 * full_next_), 3 * n,
            scratch_.triangles.indices.begin());
        if (n > 0) queue(scratch_);
        full_next_ += n;
        if (full_next_ >= shadow_.triangle_count()) full_phase_ = FullPhase::end;
        break;
      }
      case FullPhase::end:
        scratch_.type = link::MessageType::mesh_end;
        scratch_.mesh_end = link::MeshEnd{version_, shadow_.checksum()};
        queue(scratch_);
        full_active_ = false;
        break;
    }
  }
}

}  // namespace twister::station
