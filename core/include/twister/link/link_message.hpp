// Link messages between twister-station and twister-bridge (protocol version 1).
// One LinkMessage is one frame on the wire (see link_codec.hpp for the framing).
// Units: metres (positions, radius), radians (screw angle); frames are in the
// station's object frame (the mesh's own frame), the same frames the journal
// records. Every struct is fixed size: no heap.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>

namespace twister::link {

inline constexpr std::uint8_t kProtocolVersion = 1;
// Largest payload (version byte .. last body byte, without CRC) of one frame.
inline constexpr std::size_t kMaxPayload = 4096;
inline constexpr std::size_t kMaxVerticesPerChunk = 200;   // 16 bytes each
inline constexpr std::size_t kMaxTrianglesPerChunk = 300;  // 12 bytes each
inline constexpr std::size_t kLinkHands = 2;

// A pose on the wire: origin and orthonormal axes, doubles (math::Frame's fields;
// the link stays independent of the math library, its users convert).
struct Pose {
  glm::dvec3 origin{0.0};
  glm::dvec3 u{1.0, 0.0, 0.0};
  glm::dvec3 v{0.0, 1.0, 0.0};
  glm::dvec3 w{0.0, 0.0, 1.0};
};

// A screw on the wire (math::Screw's fields: spec §2).
struct Screw {
  glm::dvec3 axis{0.0, 0.0, 1.0};
  double angle = 0.0;
  double slide = 0.0;
  glm::dvec3 mid{0.0};
  glm::dvec3 chord{0.0};
  double cot_half = 0.0;
  bool pure_translation = true;
};

enum class MessageType : std::uint8_t {
  hello = 1,           // either side on connect: who it is and which mesh it holds
  mesh_begin = 2,      // starts a full mesh (full=1) or a commit's change set
  vertices = 3,        // positions of (index, xyz) vertices: chunk of a mesh/commit
  triangles = 4,       // a run of triangles starting at `first`
  mesh_end = 5,        // ends the set: next version and the mesh checksum
  live_warp = 6,       // the live stroke's screws (display warps in its shader)
  resend_request = 7,  // bridge -> station: send the full mesh
  status = 8,          // station counters (for the display's status line)
};

enum class Role : std::uint8_t { station = 1, bridge = 2 };

struct Hello {
  Role role = Role::station;
  std::uint32_t mesh_version = 0;  // 0 = holds no mesh
  std::uint64_t mesh_checksum = 0;
};

struct MeshBegin {
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
  std::uint16_t count = 0;
  std::array<VertexEntry, kMaxVerticesPerChunk> items{};
};

struct Triangles {
  std::uint32_t first = 0;  // index of the first triangle in this run
  std::uint16_t count = 0;
  std::array<std::uint32_t, 3 * kMaxTrianglesPerChunk> indices{};
};

struct MeshEnd {
  std::uint32_t version = 0;
  std::uint64_t checksum = 0;  // mesh::Mesh::checksum() of the result
};

struct LiveHand {
  Pose start{};   // grab pose (object frame)
  Pose end{};     // current pose (object frame)
  Screw screw{};  // minimal screw start -> end (spec §2)
};

struct LiveWarp {
  std::uint32_t mesh_version = 0;  // the rest mesh the warp applies to
  std::uint32_t stroke = 0;        // changes when another grab/segment starts
  bool active = false;             // false: no stroke (display shows the rest mesh)
  std::uint8_t method = 0;         // math::WarpMethod
  std::uint8_t hand_mask = 0;      // bit h: hands[h] is used
  double radius_m = 0.0;
  std::array<LiveHand, kLinkHands> hands{};
};

struct ResendRequest {
  std::uint32_t have_version = 0;
  std::uint64_t have_checksum = 0;
};

struct StatusReport {
  std::uint32_t mesh_version = 0;
  std::uint64_t strokes_committed = 0;
  std::uint64_t live_sent = 0;
  std::uint64_t live_dropped = 0;  // no room on the link: the next one replaces it
  std::uint64_t full_sends = 0;
  std::uint64_t commits_sent = 0;
  std::uint64_t frames_rejected = 0;  // frames from the bridge that failed decoding
};

// One decoded or to-be-encoded message: `type` says which member is meaningful.
struct LinkMessage {
  MessageType type = MessageType::hello;
  Hello hello{};
  MeshBegin mesh_begin{};
  Vertices vertices{};
  Triangles triangles{};
  MeshEnd mesh_end{};
  LiveWarp live_warp{};
  ResendRequest resend_request{};
  StatusReport status{};
};

}  // namespace twister::link
