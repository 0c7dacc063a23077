// SceneReplica: the bridge's copy of the station's scene, built from link messages
// (protocol 5, docs/link-protocol.md), with no OpenGL (its own library, also built
// by the fuzz preset):
//   - the mesh at a version: a full mesh or a commit's change set is staged and
//     becomes the displayed mesh only when its mesh_end checksum matches; a
//     mismatch, a change set for a version it does not hold, or chunk indices
//     outside the announced counts drop the set and ask for a full resend;
//     announced counts above the configured limits are refused before anything is
//     allocated (counted; no resend, it would bring the same);
//   - the live stroke: the same math::WarpPlan as the station (weights built once
//     per segment from the exact start frames), the screws rebuilt per update from
//     the compact end poses with the station's turn sense (link::live_screw);
//   - what the display draws besides: both hands (pose, tracked, buttons, in the
//     stroke), the radius, the object pose and the station status;
//   - the exhibit (protocol 7): the latest visitor state and the last kNoticeRing
//     notices, each with its arrival number (a display shows each one once, for a
//     while, on its own clock).
// Object frame, metres (the object pose places it in the world). Host code:
// vectors are fine here, but every size comes from a checked count.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "crease_shading.hpp"
#include "mesh_data.hpp"
#include "symmetric_live.hpp"
#include "twister/base/inline_vector.hpp"
#include "twister/link/link_message.hpp"
#include "twister/math/frame.hpp"
#include "twister/math/screw.hpp"
#include "twister/math/symmetry.hpp"
#include "twister/math/warp_method.hpp"

namespace twister::bridge {

// The largest mesh the bridge accepts (twister-bridge --max-vertices/--max-triangles).
struct ReplicaLimits {
  std::uint32_t max_vertices = 4'194'304;
  std::uint32_t max_triangles = 8'388'608;
};

struct ReplicaCounters {
  std::uint64_t full_meshes = 0;
  std::uint64_t commits = 0;
  std::uint64_t checksum_mismatches = 0;
  std::uint64_t version_gaps = 0;   // a commit for a version we do not hold
  std::uint64_t malformed = 0;      // chunk outside the announced counts
  std::uint64_t over_capacity = 0;  // announced counts above the limits (refused)
  std::uint64_t resend_requests = 0;
  std::uint64_t live_frames = 0;   // hands updates received
  std::uint64_t live_missed = 0;   // hands updates lost on the way (sequence gaps)
  std::uint64_t live_stale = 0;    // stroke for another mesh version (not drawn yet)
  std::uint64_t live_unknown = 0;  // stroke not announced yet (no stroke message)
  std::uint64_t plan_errors = 0;   // the live stroke's plan could not be built
};

// One hand as the display draws it (session hand order: 0 = hand 1, red).
struct HandView {
  bool present = false;    // a pose is known (tracked now, or held by the stroke)
  bool tracked = false;    // the station's latest sample of this hand is valid
  bool in_stroke = false;  // grabs in the open stroke: pose is the warp's end pose
  math::Frame pose{};      // object frame
  bool grab = false;       // debounced button levels
  bool radius = false;
  bool freeze = false;
  bool move_object = false;
};

// A notice as received: `number` counts notices since the replica was made (1-based),
// so a display tells a new one from one it already shows.
struct ReceivedNotice {
  link::Notice notice{};
  std::uint64_t number = 0;
};
// Notices kept (the newest; older ones are dropped, counted by notices_received()).
inline constexpr std::size_t kNoticeRing = 8;

// One plan hand of the live stroke (plan order: the stroke's hands by session index).
struct LiveHand {
  std::uint8_t session_hand = 0;
  math::Frame start{};  // exact, as the station built its plan
  math::Frame end{};    // from the compact sample
  math::Screw screw{};  // rebuilt with the station's turn sense
};

// The live stroke for the display.
struct LiveState {
  bool active = false;
  math::WarpMethod method = math::WarpMethod::twister;
  std::uint8_t hand_mask = 0;  // session hands in the stroke (bit h)
  std::uint32_t stroke = 0;
  double radius_m = 0.0;
  double refine_threshold_m = 0.0;  // the commit's refinement (0: none): the preview's too
  InlineVector<LiveHand, link::kLinkHands> hands;  // the plan's hands, in plan order
  std::vector<float> weight1, weight2;  // per vertex, plan hands 0 and 1 (0 = not influenced)
  // Per vertex (x y z each), the gradient of weight1 / weight2 at the rest position
  // (core's decay with the squash, by central differences): with the screw's own
  // derivative it gives the warped surface's normal (smooth shading while warping).
  std::vector<float> gradient1, gradient2;
  bool weights_changed = false;  // set when rebuilt; the display clears it
  // The stroke's symmetry group (docs/math.md §11; kind none: plain). Under a group the
  // display draws cpu_warp() (every image of every hand), as for scodef.
  math::SymmetrySpec symmetry{};
  // A symmetric stroke in the form the display's shader draws (symmetric_live.hpp;
  // ready false: the display keeps cpu_warp()).
  SymmetricLive symmetric_gpu;
  // Whether this stroke needs more than the plain vertex shader's warp (scodef or a
  // group): cpu_warp(), or for a group the symmetric shader when symmetric_gpu is ready.
  bool cpu_path() const {
    return method == math::WarpMethod::scodef || symmetry.kind != math::SymmetryKind::none;
  }
};

// The group a stroke message carries (StrokeBegin::symmetry: kind, mirrors, axis, order).
math::SymmetrySpec stroke_symmetry(const link::StrokeBegin& s);

class SceneReplica {
 public:
  explicit SceneReplica(ReplicaLimits limits = {});
  ~SceneReplica();
  SceneReplica(SceneReplica&&) noexcept;
  SceneReplica& operator=(SceneReplica&&) noexcept;

  // Applies one message. Returns a resend request to send when one is needed.
  std::optional<link::ResendRequest> apply(const link::LinkMessage& message);
  // A new connection: the hands' sequence starts over (no gap counted).
  void reconnected() { hands_sequence_known_ = false; }

  bool has_mesh() const { return version_ != 0; }
  std::uint32_t version() const { return version_; }
  std::uint64_t checksum() const { return checksum_; }
  const MeshData& mesh() const { return mesh_; }
  // Crease-aware shading of mesh() (crease_shading.hpp), kept with each verified
  // version: drawn vertices, their triangles and normals.
  const ShadedMesh& shading() const { return shaded_; }
  // The crease angle of shading() (degrees; default kDefaultCreaseAngleDeg).
  void set_crease_angle(float degrees);
  bool mesh_changed() const { return mesh_changed_; }
  void clear_mesh_changed() { mesh_changed_ = false; }
  LiveState& live() { return live_; }
  const LiveState& live() const { return live_; }
  // The CPU warp of the live stroke with the station's kernels (for checks and the
  // scodef preview); empty when no stroke.
  MeshData cpu_warp() const;
  const ReplicaCounters& counters() const { return counters_; }
  const ReplicaLimits& limits() const { return limits_; }

  // Display API (docs/bridge.md "SceneReplica for the display").
  const std::array<HandView, link::kLinkHands>& hands() const { return hands_; }
  float radius_m() const { return radius_m_; }
  // The object frame in the world (identity until the station sends it).
  const math::Frame& object_pose() const { return object_pose_; }
  // The station's working volume and up axis (protocol 5), in the world.
  bool has_workspace() const { return has_workspace_; }
  const link::Workspace& workspace() const { return workspace_; }
  bool has_status() const { return has_status_; }
  const link::StatusReport& station_status() const { return status_; }
  // The exhibit's visitor lifecycle (protocol 7): false until the station sends one
  // (a station without the exhibit never does).
  bool has_visitor() const { return has_visitor_; }
  const link::VisitorState& visitor() const { return visitor_; }
  // The newest notices, oldest first (at most kNoticeRing), and how many ever came.
  std::vector<ReceivedNotice> notices() const;
  std::uint64_t notices_received() const { return notices_received_; }

 private:
  struct Plan;
  std::optional<link::ResendRequest> request();
  void begin(const link::MeshBegin& b);
  void on_vertices(const link::Vertices& v);
  void on_triangles(const link::Triangles& t);
  void end(const link::MeshEnd& e, std::optional<link::ResendRequest>& out);
  void on_stroke(const link::StrokeBegin& s);
  void on_hands(const link::Hands& h);
  void update_live(const link::Hands& h);
  bool ensure_plan();
  void fill_gradients(const std::array<math::Frame, 2>& start, std::size_t hands);
  // The cached symmetric plan follows the live hands (the station's turn sense).
  bool follow_hands() const;
  // symmetric_gpu's entries (per grab) and images (per hands update).
  void build_symmetric_gpu();
  void update_symmetric_images();

  ReplicaLimits limits_;
  MeshData mesh_;
  ShadedMesh shaded_;
  float crease_angle_deg_ = kDefaultCreaseAngleDeg;
  std::uint32_t version_ = 0;
  std::uint64_t checksum_ = 0;
  bool mesh_changed_ = false;
  // Change set being received.
  bool staging_ = false;
  bool staging_bad_ = false;
  link::MeshBegin begin_{};
  MeshData staged_;
  // Live stroke.
  LiveState live_;
  bool stroke_known_ = false;
  link::StrokeBegin stroke_{};
  std::unique_ptr<Plan> plan_;  // weights of stroke_ on mesh_ (built lazily)
  std::uint16_t hands_sequence_ = 0;
  bool hands_sequence_known_ = false;
  std::array<HandView, link::kLinkHands> hands_{};
  float radius_m_ = 0.0F;
  math::Frame object_pose_{};
  bool has_status_ = false;
  link::StatusReport status_{};
  bool has_workspace_ = false;
  link::Workspace workspace_{};
  bool has_visitor_ = false;
  link::VisitorState visitor_{};
  std::array<ReceivedNotice, kNoticeRing> notices_{};  // ring: number n at (n - 1) % size
  std::uint64_t notices_received_ = 0;
  ReplicaCounters counters_{};
};

// For tests and benchmarks: the `stroke` and `hands` messages a station sends for
// a stroke of the session hands in `hand_mask` from `start` to `end` (plan order),
// with the screws math::compute_screw gives (previous axes as given).
struct LiveMessages {
  link::StrokeBegin stroke;
  link::Hands hands;
};
LiveMessages make_live_messages(std::uint32_t mesh_version, std::uint32_t stroke,
                                math::WarpMethod method, double radius_m, std::uint8_t hand_mask,
                                const std::array<math::Frame, 2>& start,
                                const std::array<math::Frame, 2>& end,
                                const std::array<math::Screw, 2>* screws = nullptr);

}  // namespace twister::bridge
