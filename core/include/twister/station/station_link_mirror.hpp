// MeshMirror: the display's copy of the committed mesh. Keeps a shadow of the mesh
// the display was sent (caller storage, at least the mesh's capacity) and its
// version; per commit it queues one change set on the bulk queue (vertices whose
// bits changed or that are new, runs of triangles that changed or are new, the
// counts after the commit, version and checksum), all or nothing; a commit that
// does not fit, a resend request or a display holding another mesh gets a full
// send from the shadow, a few frames per poll. Spectators (issue 25) share the
// shadow and each commit's encoded change set (staged() after track(): the main
// display's bytes when it was sent one, else encoded once into the staging buffer);
// each keeps only where its own full send stands (MeshSendState). No heap. Not
// thread-safe.
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

// Frames encoded into caller storage, all or nothing per commit (the staged change
// set spectators copy).
class FrameBuffer {
 public:
  FrameBuffer() = default;
  explicit FrameBuffer(std::span<std::byte> bytes) : bytes_(bytes) {}
  template <link::LinkBody M>
  bool bulk(const M& m) {
    const Result<std::size_t> n = link::encode_frame(m, bytes_.subspan(size_));
    if (!n.ok()) return false;
    size_ += *n;
    return true;
  }
  std::size_t bulk_mark() const { return size_; }
  void bulk_rewind(std::size_t mark) { size_ = mark < size_ ? mark : size_; }
  std::span<const std::byte> bytes() const {
    return std::span<const std::byte>(bytes_).first(size_);
  }
  void clear() { size_ = 0; }

 private:
  std::span<std::byte> bytes_{};
  std::size_t size_ = 0;
};

struct MirrorCounters {
  std::uint64_t full_sends = 0;
  std::uint64_t commits_sent = 0;
};

// One receiver's full send: due, in progress (and where), how many began.
struct MeshSendState {
  enum class Phase : std::uint8_t { begin, vertices, triangles, end };
  bool wanted = false;
  bool active = false;
  Phase phase = Phase::begin;
  std::size_t next = 0;
  std::uint64_t full_sends = 0;
  bool idle() const { return !active && !wanted; }
  // A commit arrived: a full send in progress restarts from the fresh shadow.
  void restart() {
    phase = Phase::begin;
    next = 0;
  }
};

class MeshMirror {
 public:
  // `staging`: where a commit's change set is encoded for spectators when the main
  // display was not sent it (empty: spectators get full sends then).
  MeshMirror(FrameQueues& out, MeshMirrorStorage storage, std::span<std::byte> staging = {})
      : out_(out),
        shadow_(storage.x, storage.y, storage.z, storage.triangle_indices),
        staging_(staging) {}

  // Takes `mesh` as version 1. resource_exhausted: the shadow is too small.
  Status start(const mesh::Mesh& mesh);
  // A commit changed `mesh`: a new version, sent as a change set when `send` (a
  // display is admitted) and nothing else is on its way, else a full send. With
  // `stage` (a spectator is current) the change set is also left in staged().
  void track(const mesh::Mesh& mesh, bool send, bool stage = false);
  // The last track()'s encoded change set (empty: none, or it did not fit); valid
  // until the main display's queues are next flushed or tracked again.
  std::span<const std::byte> staged() const { return staged_; }
  // A display holding `holds` was admitted: a full send unless it holds ours.
  void resync(const MeshIdentity& holds);
  void want_full() { main_.wanted = true; }
  // The display is gone: nothing is on its way any more.
  void cancel() {
    main_.active = false;
    main_.wanted = false;
  }
  // Queues what the bulk queue has room for of a full send due or in progress.
  void send() { send(main_, out_); }
  // The same for another receiver (a spectator) on its own queues.
  void resync(MeshSendState& state, const MeshIdentity& holds);
  void send(MeshSendState& state, FrameQueues& out);

  // The mesh the display gets (or holds): version and checksum.
  // The checksum is computed when first asked after a commit, not at every commit.
  MeshIdentity offered();
  std::uint32_t version() const { return version_; }
  bool idle() const { return main_.idle(); }
  MirrorCounters counters() const { return MirrorCounters{main_.full_sends, commits_sent_}; }

 private:
  template <class Out>
  bool queue_commit(Out& out, const mesh::Mesh& mesh, std::uint32_t old_vertices,
                    std::uint32_t old_triangles);
  template <class Out>
  bool queue_changed_vertices(Out& out, const mesh::Mesh& mesh, std::uint32_t old_vertices);
  template <class Out>
  bool queue_changed_triangles(Out& out, const mesh::Mesh& mesh, std::uint32_t old_triangles);
  void continue_full(MeshSendState& state, FrameQueues& out);
  void full_vertices(MeshSendState& state, FrameQueues& out);
  void full_triangles(MeshSendState& state, FrameQueues& out);

  FrameQueues& out_;
  mesh::Mesh shadow_;
  std::uint32_t version_ = 0;
  std::uint64_t checksum_ = 0;  // the shadow's, when checksum_stale_ is false
  bool checksum_stale_ = false;
  MeshSendState main_{};  // the main display's full send
  std::uint64_t commits_sent_ = 0;
  FrameBuffer staging_;
  std::span<const std::byte> staged_{};
  // The chunk being built (large: kept off the stack).
  link::Vertices vertices_{};
  link::Triangles triangles_{};
};

}  // namespace twister::station
