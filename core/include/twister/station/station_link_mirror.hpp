// MeshMirror: the display's copy of the committed mesh. Keeps a shadow of the mesh
// the display was sent (caller storage, at least the mesh's capacity) and its
// version; per commit it queues one change set on the bulk queue (vertices whose
// bits changed or that are new, runs of triangles that changed or are new, the
// counts after the commit, version and checksum), all or nothing; a commit that
// does not fit, a resend request or a display holding another mesh gets a full
// send from the shadow, a few frames per poll. No heap. Not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/link/link_message.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/station/station_link_admission.hpp"
#include "twister/station/station_link_queues.hpp"

namespace twister::station {

struct MeshMirrorStorage {
  std::span<float> x;  // each at least the mesh's vertex capacity
  std::span<float> y;
  std::span<float> z;
  std::span<std::uint32_t> triangle_indices;  // 3 * triangle capacity
};

struct MirrorCounters {
  std::uint64_t full_sends = 0;
  std::uint64_t commits_sent = 0;
};

class MeshMirror {
 public:
  MeshMirror(FrameQueues& out, MeshMirrorStorage storage)
      : out_(out), shadow_(storage.x, storage.y, storage.z, storage.triangle_indices) {}

  // Takes `mesh` as version 1. resource_exhausted: the shadow is too small.
  Status start(const mesh::Mesh& mesh);
  // A commit changed `mesh`: a new version, sent as a change set when `send` (a
  // display is admitted) and nothing else is on its way, else a full send.
  void track(const mesh::Mesh& mesh, bool send);
  // A display holding `holds` was admitted: a full send unless it holds ours.
  void resync(const MeshIdentity& holds);
  void want_full() { full_wanted_ = true; }
  // The display is gone: nothing is on its way any more.
  void cancel() {
    full_active_ = false;
    full_wanted_ = false;
  }
  // Queues what the bulk queue has room for of a full send due or in progress.
  void send();

  // The mesh the display gets (or holds): version and checksum.
  // The checksum is computed when first asked after a commit, not at every commit.
  MeshIdentity offered();
  std::uint32_t version() const { return version_; }
  bool idle() const { return !full_active_ && !full_wanted_; }
  const MirrorCounters& counters() const { return counters_; }

 private:
  enum class FullPhase : std::uint8_t { begin, vertices, triangles, end };

  bool queue_commit(const mesh::Mesh& mesh, std::uint32_t old_vertices,
                    std::uint32_t old_triangles);
  bool queue_changed_vertices(const mesh::Mesh& mesh, std::uint32_t old_vertices);
  bool queue_changed_triangles(const mesh::Mesh& mesh, std::uint32_t old_triangles);
  void continue_full();
  void full_vertices();
  void full_triangles();

  FrameQueues& out_;
  mesh::Mesh shadow_;
  std::uint32_t version_ = 0;
  std::uint64_t checksum_ = 0;  // the shadow's, when checksum_stale_ is false
  bool checksum_stale_ = false;
  bool full_wanted_ = false;
  bool full_active_ = false;
  FullPhase full_phase_ = FullPhase::begin;
  std::size_t full_next_ = 0;
  // The chunk being built (large: kept off the stack).
  link::Vertices vertices_{};
  link::Triangles triangles_{};
  MirrorCounters counters_{};
};

}  // namespace twister::station
