// SceneReplica: the bridge's copy of the station's scene. A versioned mesh built
// from link messages (full mesh or commit change sets, each ending with the
// station's version and checksum) and the live stroke (the station's screws; the
// bridge rebuilds the stroke's weights once per stroke with the same core
// WarpPlan the station uses, so the display can warp in its vertex shader).
// A commit for another base version or a checksum mismatch drops the change set
// and asks for a full resend; the displayed mesh stays the last verified one.
// Object frame, metres. Host code: vectors are fine here.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "twister/link/link_message.hpp"
#include "twister/math/warp_method.hpp"
#include "twister/meshio/mesh_buffer.hpp"

namespace twister::bridge {

struct MeshData {
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> indices;  // 3 per triangle
  std::size_t vertex_count() const { return x.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
};

// The data as a core mesh::Mesh (for the station's checksum and OBJ writer); null
// when a triangle index is out of range.
std::unique_ptr<meshio::MeshBuffer> to_core_mesh(const MeshData& mesh);
// mesh::Mesh::checksum() of the data; nullopt when a triangle index is out of range.
std::optional<std::uint64_t> mesh_checksum(const MeshData& mesh);

struct ReplicaCounters {
  std::uint64_t full_meshes = 0;
  std::uint64_t commits = 0;
  std::uint64_t checksum_mismatches = 0;
  std::uint64_t version_gaps = 0;  // a commit for a version we do not hold
  std::uint64_t malformed = 0;     // chunk outside the announced counts
  std::uint64_t resend_requests = 0;
  std::uint64_t live_frames = 0;
  std::uint64_t live_stale = 0;   // for another mesh version (ignored)
  std::uint64_t plan_errors = 0;  // the live stroke's plan could not be built
};

// Per-vertex stroke data for the display.
struct LiveState {
  bool active = false;
  math::WarpMethod method = math::WarpMethod::twister;
  std::uint8_t hand_mask = 0;
  std::uint32_t stroke = 0;
  link::LiveWarp message{};
  std::vector<float> weight1, weight2;  // per vertex (0 = not influenced)
  bool weights_changed = false;         // set when rebuilt; the display clears it
};

class SceneReplica {
 public:
  // Applies one message. Returns a resend request to send when one is needed.
  std::optional<link::ResendRequest> apply(const link::LinkMessage& message);
  // Hello to send after (re)connecting: resync by version.
  link::Hello hello() const;

  bool has_mesh() const { return version_ != 0; }
  std::uint32_t version() const { return version_; }
  std::uint64_t checksum() const { return checksum_; }
  const MeshData& mesh() const { return mesh_; }
  bool mesh_changed() const { return mesh_changed_; }
  void clear_mesh_changed() { mesh_changed_ = false; }
  LiveState& live() { return live_; }
  const LiveState& live() const { return live_; }
  // The CPU warp of the live stroke with the station's own kernel (for checks and
  // the scodef preview); empty when no stroke.
  MeshData cpu_warp() const;
  const ReplicaCounters& counters() const { return counters_; }
  const link::StatusReport& station_status() const { return status_; }

 private:
  std::optional<link::ResendRequest> request();
  void begin(const link::MeshBegin& b);
  void end(const link::MeshEnd& e, std::optional<link::ResendRequest>& out);
  void on_live(const link::LiveWarp& l);
  void rebuild_weights();

  MeshData mesh_;
  std::uint32_t version_ = 0;
  std::uint64_t checksum_ = 0;
  bool mesh_changed_ = false;
  // Change set being received.
  bool staging_ = false;
  bool staging_bad_ = false;
  link::MeshBegin begin_{};
  MeshData staged_;
  LiveState live_;
  link::StatusReport status_{};
  ReplicaCounters counters_{};
};

}  // namespace twister::bridge
