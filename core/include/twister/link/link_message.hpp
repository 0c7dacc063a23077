// Link messages between twister-station and twister-bridge (protocol version 6,
// docs/link-protocol.md). Each message type is its own small struct naming its
// MessageType (kType); one frame on the wire carries one of them (see
// link_codec.hpp for the framing). LinkMessage, a std::variant of all sixteen, is
// what a decoder yields: senders encode the type they send directly and never
// build a LinkMessage for it. Units: metres, radians; poses are in the station's
// object frame (the mesh's own frame, the journal's frames) except the object pose,
// which places the object in the world. Every struct is fixed size: no heap.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <type_traits>
#include <variant>

#include "twister/base/pose.hpp"

namespace twister::link {

inline constexpr std::uint8_t kProtocolVersion = 7;
// Largest payload (version byte .. last body byte, without CRC) of one frame.
inline constexpr std::size_t kMaxPayload = 4096;
inline constexpr std::size_t kMaxVerticesPerChunk = 200;   // 16 bytes each
inline constexpr std::size_t kMaxTrianglesPerChunk = 300;  // 12 bytes each
inline constexpr std::size_t kLinkHands = 2;
inline constexpr std::size_t kNonceBytes = 16;
inline constexpr std::size_t kAuthTagBytes = 32;

// A compact pose: position and orientation as a unit quaternion (w, x, y, z),
// floats (28 bytes on the wire). The quaternion's sign carries information where a
// stroke is open (see Hands).
struct CompactPose {
  glm::vec3 position{0.0F};
  std::array<float, 4> rotation{1.0F, 0.0F, 0.0F, 0.0F};  // w, x, y, z
};

enum class MessageType : std::uint8_t {
  hello = 1,           // both, on connect: who, which mesh, a nonce
  auth = 2,            // both: the challenge-response tag (links with a key)
  bye = 3,             // both: the link ends, and why (the peer backs off)
  mesh_begin = 4,      // S->B: starts a full mesh (full=1) or a commit's change set
  vertices = 5,        // S->B: (index, xyz) vertices of a mesh or change set
  triangles = 6,       // S->B: a run of triangles starting at `first` (new or changed)
  mesh_end = 7,        // S->B: ends the set: next version and the mesh checksum
  resend_request = 8,  // B->S: send the full mesh
  stroke = 9,          // S->B: a live stroke segment starts: exact start frames
  hands = 10,          // S->B: tracker-rate update: hands, buttons, radius, live stroke
  object = 11,         // S->B: the object's pose in the world
  status = 12,         // S->B: station status (tracker, capacity, counters)
  command = 13,        // B->S: a sculptor's key (undo, redo, method), admitted display only
  workspace = 14,      // S->B: the hands' working volume and the up axis (protocol 5)
  visitor = 15,        // S->B: the exhibit's visitor lifecycle (protocol 7)
  notice = 16,         // S->B: a short reason shown on screen (protocol 7)
};
inline constexpr std::uint8_t kLastMessageType = 16;

enum class Role : std::uint8_t { station = 1, bridge = 2 };

// Hello flags.
inline constexpr std::uint8_t kHelloAuth = 1;  // the sender holds a key: challenge-response
// A displaced display trying again: admit it only while no display holds the link
// (otherwise bye: busy), so two displays never take the link from each other.
inline constexpr std::uint8_t kHelloYield = 2;
// A read-only display (protocol 7): receives the same stream as the display that may
// send commands, never displaces it, and its commands are refused (notice).
inline constexpr std::uint8_t kHelloSpectator = 4;
inline constexpr std::uint8_t kHelloFlagMask = 7;

struct Hello {
  static constexpr MessageType kType = MessageType::hello;
  Role role = Role::station;
  std::uint8_t flags = 0;
  std::uint32_t mesh_version = 0;  // 0 = holds no mesh
  std::uint64_t mesh_checksum = 0;
  std::array<std::uint8_t, kNonceBytes> nonce{};  // fresh per connection (auth)
};

struct Auth {
  static constexpr MessageType kType = MessageType::auth;
  std::array<std::uint8_t, kAuthTagBytes> tag{};
};

enum class ByeReason : std::uint8_t {
  shutdown = 1,      // the station stops
  displaced = 2,     // another (authorised) display took the link: retry yielding
  unauthorised = 3,  // authentication failed or missing
  protocol = 4,      // the peer broke the protocol (wrong role, version, order)
  timeout = 5,       // the handshake took too long
  busy = 6,          // a yielding hello while another display holds the link: later
};
inline constexpr std::uint8_t kLastByeReason = 6;

struct Bye {
  static constexpr MessageType kType = MessageType::bye;
  ByeReason reason = ByeReason::shutdown;
};

struct MeshBegin {
  static constexpr MessageType kType = MessageType::mesh_begin;
  bool full = true;                // true: replace the mesh; false: a commit
  std::uint32_t base_version = 0;  // a commit applies to this version only
  std::uint32_t version = 0;       // version after mesh_end
  std::uint32_t vertex_count = 0;  // counts after the set is applied
  std::uint32_t triangle_count = 0;
};

struct VertexEntry {
  std::uint32_t index = 0;
  float x = 0.0F;
  float y = 0.0F;
  float z = 0.0F;
};

struct Vertices {
  static constexpr MessageType kType = MessageType::vertices;
  std::uint16_t count = 0;
  std::array<VertexEntry, kMaxVerticesPerChunk> items{};
};

struct Triangles {
  static constexpr MessageType kType = MessageType::triangles;
  std::uint32_t first = 0;  // index of the first triangle in this run
  std::uint16_t count = 0;
  std::array<std::uint32_t, 3 * kMaxTrianglesPerChunk> indices{};
};

struct MeshEnd {
  static constexpr MessageType kType = MessageType::mesh_end;
  std::uint32_t version = 0;
  std::uint64_t checksum = 0;  // mesh::Mesh::checksum() of the result
};

struct ResendRequest {
  static constexpr MessageType kType = MessageType::resend_request;
  std::uint32_t have_version = 0;
  std::uint64_t have_checksum = 0;
};

// A stroke segment begins (and is repeated about once a second while it lasts, so a
// bridge that connects mid-stroke picks it up): everything the bridge needs to
// build the same math::WarpPlan as the station, exactly.
struct StrokeBegin {
  static constexpr MessageType kType = MessageType::stroke;
  std::uint32_t stroke = 0;        // segment id (+1 per segment)
  std::uint32_t mesh_version = 0;  // the rest mesh it warps
  std::uint8_t method = 0;         // math::WarpMethod
  std::uint8_t hand_mask = 0;      // session hands in the segment (bit h), 1..3
  // The refinement threshold the segment's commit refines with (metres; 0: the
  // commit is not refined): the display refines its live preview to the same.
  float refine_threshold_m = 0.0F;
  double radius_m = 0.0;
  std::array<twister::Pose, kLinkHands> start{};  // exact; per session hand in hand_mask
  // The segment's symmetry group (protocol 5, docs/math.md §11), as the journal's
  // version 5 stroke records carry it: kind 0 none, 1 mirrors (planes: bits x, y, z),
  // 2 n-fold rotation about axis 0..2, 3 with the mirrors through it (order 2..12);
  // unused fields 0. A display draws the images from it (the live warp of every image).
  std::array<std::uint8_t, 4> symmetry{};  // kind, mirrors, axis, order
};

// Hands flags.
inline constexpr std::uint8_t kHandSample0 = 1;    // hands[0] is on the wire
inline constexpr std::uint8_t kHandSample1 = 2;    // hands[1] is on the wire
inline constexpr std::uint8_t kHandTracked0 = 4;   // hand 0's latest pose is valid
inline constexpr std::uint8_t kHandTracked1 = 8;   // hand 1's latest pose is valid
inline constexpr std::uint8_t kStrokeActive = 16;  // a stroke segment is open
inline constexpr std::uint8_t kHandsFlagMask = 31;
// Buttons: 4 bits per hand (hand 1 shifted by 4).
inline constexpr std::uint8_t kButtonGrab = 1;
inline constexpr std::uint8_t kButtonRadius = 2;
inline constexpr std::uint8_t kButtonFreeze = 4;
inline constexpr std::uint8_t kButtonMoveObject = 8;

// The tracker-rate update (two hands: 74 bytes on the wire, kHandsFrameBytes). A hand's sample is
// its pose in the object frame; for a hand in the open stroke it is the warp's end pose and the
// quaternion's sign tells which way the hand turned: with q_start the start frame's quaternion
// (frame_quaternion), q_rel = rotation * conj(q_start) has w >= 0 for a turn of at most a half turn
// and its vector part along the station's screw axis (docs/link-protocol.md "Live warp").
inline constexpr std::size_t kHandsFrameBytes = 74;  // two hands (tested)

struct Hands {
  static constexpr MessageType kType = MessageType::hands;
  std::uint16_t sequence = 0;  // +1 per hands message: the bridge counts gaps
  std::uint16_t stroke = 0;    // low 16 bits of the open segment's id
  std::uint8_t flags = 0;
  std::uint8_t buttons = 0;
  float radius_m = 0.0F;  // the session's current radius
  std::array<CompactPose, kLinkHands> hands{};
};

struct ObjectPose {
  static constexpr MessageType kType = MessageType::object;
  CompactPose pose{};  // the object frame in the world
};

// Tracker states in StatusReport.
enum class TrackerState : std::uint8_t { starting = 0, streaming = 1, lost = 2 };

// Button device states in StatusReport (protocol 4).
enum class ButtonsState : std::uint8_t { present = 0, missing = 1 };

// The session's stroke counters in StatusReport.
struct StrokeCounts {
  std::uint64_t committed = 0;
  std::uint64_t not_saved = 0;       // commits whose journal append failed
  std::uint64_t capacity_stops = 0;  // refined commits stopped by the mesh's capacity
};

// The link's own traffic counters in StatusReport (StationLink's, not the session's).
struct LinkTraffic {
  std::uint64_t live_sent = 0;
  std::uint64_t live_dropped = 0;  // no room on the link: the next one replaces it
  std::uint64_t frames_rejected = 0;
};

// Station status, about once a second and when something in it changes.
struct StatusReport {
  static constexpr MessageType kType = MessageType::status;
  std::uint32_t mesh_version = 0;
  std::uint32_t vertex_count = 0;
  std::uint32_t vertex_capacity = 0;
  std::uint32_t triangle_count = 0;
  std::uint32_t triangle_capacity = 0;
  std::uint8_t tracker_state = 0;  // TrackerState
  std::uint8_t buttons_state = 0;  // ButtonsState (protocol 4): the button device missing
  float tracker_rate_hz = 0.0F;    // poses used per second (both hands)
  std::uint8_t method = 0;         // math::WarpMethod of the next stroke
  std::uint8_t clutch = 0;         // bit h: hand h's clutch is in (freeze held)
  float turned_rad = 0.0F;         // the most any hand has turned in the open stroke
  float turn_limit_rad = 0.0F;     // limit of one stroke; 0 = not reported
  StrokeCounts strokes{};
  LinkTraffic traffic{};
  // Protocol 7: the next stroke's symmetry group (StrokeBegin::symmetry's bytes) and
  // the read-only displays admitted now.
  std::array<std::uint8_t, 4> symmetry{};
  std::uint8_t spectators = 0;
};

// A command from the display's keyboard, routed by the station into the session's
// command path (the same as the hands' undo/redo/method buttons). The station acts
// only on an admitted display's commands.
enum class CommandKind : std::uint8_t {
  undo = 1,
  redo = 2,
  next_method = 3,
  set_method = 4,
  cycle_symmetry = 5,      // protocol 7: the next stroke's group, in the config's cycle
  new_sculpture = 6,       // protocol 7: end this visitor's sculpture (archive, reset)
  undo_new_sculpture = 7,  // protocol 7: within the grace time, bring it back
};
inline constexpr std::uint8_t kLastCommandKind = 7;

struct Command {
  static constexpr MessageType kType = MessageType::command;
  CommandKind kind = CommandKind::undo;
  std::uint8_t method = 0;  // math::WarpMethod, set_method only
};

// Workspace flags.
inline constexpr std::uint8_t kWorkspaceCalibrated = 1;  // a calibrated work frame: up is +Z
inline constexpr std::uint8_t kWorkspaceConfigured = 2;  // the volume comes from the config
inline constexpr std::uint8_t kWorkspaceFlagMask = 3;

// The space the hands work in (protocol 5), in the object frame (metres): an
// axis-aligned box and the up direction. Sent once after each admission; the
// kiosk and offscreen cameras frame it (docs/bridge.md "Window, kiosk, camera").
struct Workspace {
  static constexpr MessageType kType = MessageType::workspace;
  std::uint8_t flags = 0;  // kWorkspaceCalibrated | kWorkspaceConfigured
  glm::vec3 up{0.0F, 0.0F, -1.0F};
  glm::vec3 min{0.0F};
  glm::vec3 max{0.0F};
};

// The exhibit's visitor lifecycle (protocol 7, docs/interaction.md "A day at the
// exhibit"): sent when it changes and about once a second.
enum class VisitorPhase : std::uint8_t { attract = 0, sculpting = 1, finished = 2 };
inline constexpr std::uint8_t kLastVisitorPhase = 2;
// VisitorState flags.
inline constexpr std::uint8_t kVisitorResetUndoable = 1;  // "undo the reset" is open
inline constexpr std::uint8_t kVisitorArchiveFailed = 2;  // the last archive was not written
inline constexpr std::uint8_t kVisitorDiskFull = 4;       // the archive's disk is full
inline constexpr std::uint8_t kVisitorFlagMask = 7;

struct VisitorState {
  static constexpr MessageType kType = MessageType::visitor;
  VisitorPhase phase = VisitorPhase::attract;
  std::uint8_t flags = 0;
  std::uint32_t visitor = 0;    // today's visitor number, 1-based (0: none yet)
  std::uint32_t sculpture = 0;  // the sculpture's id (the archive's number)
  std::uint32_t strokes = 0;    // strokes committed in this sculpture
  float idle_left_s = 0.0F;     // until an idle sculpture ends (0: not counting)
  float grace_left_s = 0.0F;    // "undo the reset" time left (0: none)
};

// Why nothing happened, or what just happened (protocol 7): the display shows it
// briefly. `detail` qualifies some codes (documented per code in link-protocol.md).
enum class NoticeCode : std::uint8_t {
  undo_refused = 1,               // nothing to undo (or a stroke is open)
  redo_refused = 2,               // nothing to redo
  command_refused_spectator = 3,  // a read-only display sent a command
  nothing_to_act_on = 4,          // a gesture found nothing (e.g. a grab with no vertex)
  sculpture_archived = 5,         // a sculpture ended and was archived
  archive_failed = 6,             // it ended but its archive was not written
  disk_full = 7,                  // the archive's disk is full: sculpting goes on
  new_sculpture_undone = 8,       // the reset was undone within the grace time
  symmetry_changed = 9,           // the next stroke's group changed (see status)
};
inline constexpr std::uint8_t kLastNoticeCode = 9;

struct Notice {
  static constexpr MessageType kType = MessageType::notice;
  NoticeCode code = NoticeCode::undo_refused;
  std::uint8_t detail = 0;
};

// One decoded message: the alternative is its type, in MessageType order (index
// + 1 is the type byte). As large as its largest alternative (Triangles) plus the
// index: only decoders hold one.
using LinkMessage = std::variant<Hello, Auth, Bye, MeshBegin, Vertices, Triangles, MeshEnd,
                                 ResendRequest, StrokeBegin, Hands, ObjectPose, StatusReport,
                                 Command, Workspace, VisitorState, Notice>;
static_assert(std::variant_size_v<LinkMessage> == kLastMessageType);

inline MessageType type_of(const LinkMessage& m) { return static_cast<MessageType>(m.index() + 1); }

namespace internal {
template <class T, class Variant>
struct IsAlternative;
template <class T, class... Ts>
struct IsAlternative<T, std::variant<Ts...>> : std::bool_constant<(std::is_same_v<T, Ts> || ...)> {
};
}  // namespace internal

// A message body type: one of LinkMessage's alternatives.
template <class T>
concept LinkBody = internal::IsAlternative<T, LinkMessage>::value;

}  // namespace twister::link
