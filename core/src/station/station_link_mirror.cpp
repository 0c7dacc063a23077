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

void MeshMirror::resync(const MeshIdentity& holds) { resync(main_, holds); }

void MeshMirror::resync(MeshSendState& state, const MeshIdentity& holds) {
  // Resync by version: a display that holds exactly our mesh gets nothing again.
  if (holds != offered()) state.wanted = true;
}

void MeshMirror::track(const mesh::Mesh& mesh, bool send, bool stage) {
  const auto old_vertices = static_cast<std::uint32_t>(shadow_.vertex_count());
  const auto old_triangles = static_cast<std::uint32_t>(shadow_.triangle_count());
  ++version_;
  checksum_stale_ = true;  // a commit queued for the display computes it now
  staged_ = {};
  const std::size_t mark = out_.bulk_mark();
  const bool sent = send && main_.idle() && queue_commit(out_, mesh, old_vertices, old_triangles);
  if (sent) ++commits_sent_;
  if (stage && sent) {
    staged_ = out_.bulk_since(mark);  // the spectators copy the main display's bytes
  } else if (stage) {
    staging_.clear();
    if (queue_commit(staging_, mesh, old_vertices, old_triangles)) staged_ = staging_.bytes();
  }
  if (!shadow_.copy_from(mesh).ok()) {
    // Larger than the shadow (cannot happen when sized from the mesh capacity).
    shadow_.clear();
    checksum_stale_ = true;
  }
  if (main_.active) {
    main_.restart();
  } else if (!sent && send) {
    main_.wanted = true;
  }
}

template <class Out>
bool MeshMirror::queue_commit(Out& out, const mesh::Mesh& mesh, std::uint32_t old_vertices,
                              std::uint32_t old_triangles) {
  const std::size_t mark = out.bulk_mark();
  bool ok = out.bulk(link::MeshBegin{false, version_ - 1, version_,
                                     static_cast<std::uint32_t>(mesh.vertex_count()),
                                     static_cast<std::uint32_t>(mesh.triangle_count())}) &&
            queue_changed_vertices(out, mesh, old_vertices) &&
            queue_changed_triangles(out, mesh, old_triangles);
  checksum_ = mesh.checksum();  // the shadow's once it is copied from `mesh`
  checksum_stale_ = false;
  ok = ok && out.bulk(link::MeshEnd{version_, checksum_});
  if (!ok) {
    out.bulk_rewind(mark);  // all or nothing: never a half commit in the buffer
    return false;
  }
  return true;
}

template <class Out>
bool MeshMirror::queue_changed_vertices(Out& out, const mesh::Mesh& mesh,
                                        std::uint32_t old_vertices) {
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
      if (!out.bulk(vertices_)) return false;
      vertices_.count = 0;
    }
  }
  return vertices_.count == 0 || out.bulk(vertices_);
}

template <class Out>
bool MeshMirror::queue_changed_triangles(Out& out, const mesh::Mesh& mesh,
                                         std::uint32_t old_triangles) {
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
    if (!out.bulk(triangles_)) return false;
    t += run;
  }
  return true;
}

void MeshMirror::send(MeshSendState& state, FrameQueues& out) {
  if (state.wanted && !state.active) {
    state.wanted = false;
    state.active = true;
    state.restart();
    ++state.full_sends;
  }
  if (state.active) continue_full(state, out);
}

void MeshMirror::full_vertices(MeshSendState& state, FrameQueues& out) {
  const std::size_t n = std::min(link::kMaxVerticesPerChunk, shadow_.vertex_count() - state.next);
  vertices_.count = static_cast<std::uint16_t>(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::uint32_t>(state.next + k);
    const glm::vec3 p = shadow_.position(i);
    vertices_.items[k] = link::VertexEntry{i, p.x, p.y, p.z};
  }
  if (n > 0) (void)out.bulk(vertices_);
  state.next += n;
  if (state.next >= shadow_.vertex_count()) {
    state.phase = MeshSendState::Phase::triangles;
    state.next = 0;
  }
}

void MeshMirror::full_triangles(MeshSendState& state, FrameQueues& out) {
  const std::size_t n =
      std::min(link::kMaxTrianglesPerChunk, shadow_.triangle_count() - state.next);
  triangles_.first = static_cast<std::uint32_t>(state.next);
  triangles_.count = static_cast<std::uint16_t>(n);
  std::copy_n(shadow_.triangle_indices().begin() + static_cast<std::ptrdiff_t>(3 * state.next),
              3 * n, triangles_.indices.begin());
  if (n > 0) (void)out.bulk(triangles_);
  state.next += n;
  if (state.next >= shadow_.triangle_count()) state.phase = MeshSendState::Phase::end;
}

void MeshMirror::continue_full(MeshSendState& state, FrameQueues& out) {
  // A few frames per poll keep the loop responsive; the rest follows next poll.
  using Phase = MeshSendState::Phase;
  while (state.active && out.bulk_room() >= link::kMaxFrameBytes) {
    switch (state.phase) {
      case Phase::begin:
        (void)out.bulk(link::MeshBegin{true, 0, version_,
                                       static_cast<std::uint32_t>(shadow_.vertex_count()),
                                       static_cast<std::uint32_t>(shadow_.triangle_count())});
        state.phase = Phase::vertices;
        state.next = 0;
        break;
      case Phase::vertices:
        full_vertices(state, out);
        break;
      case Phase::triangles:
        full_triangles(state, out);
        break;
      case Phase::end:
        (void)out.bulk(link::MeshEnd{version_, offered().checksum});
        state.active = false;
        break;
    }
  }
}

}  // namespace twister::station
