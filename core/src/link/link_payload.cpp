// Message bodies: one write / read pair per message type, same field order.
// Readers refuse out-of-range fields and non-finite numbers (a NaN pose would
// poison the display's shader); counts are bounded by the chunk capacities.
#include "link_payload.hpp"

#include <cmath>

namespace twister::link::internal {
namespace {

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void write_pose(ByteWriter& w, const Pose& f) {
  w.vec(f.origin);
  w.vec(f.u);
  w.vec(f.v);
  w.vec(f.w);
}

Pose read_pose(ByteReader& r, bool& bad) {
  Pose f;
  f.origin = r.vec();
  f.u = r.vec();
  f.v = r.vec();
  f.w = r.vec();
  bad = bad || !finite(f.origin) || !finite(f.u) || !finite(f.v) || !finite(f.w);
  return f;
}

void write_compact(ByteWriter& w, const CompactPose& p) {
  w.f32(p.position.x);
  w.f32(p.position.y);
  w.f32(p.position.z);
  for (const float q : p.rotation) w.f32(q);
}

// A rotation must be a (nearly) unit quaternion: the bridge normalises it.
CompactPose read_compact(ByteReader& r, bool& bad) {
  CompactPose p;
  p.position = {r.f32(), r.f32(), r.f32()};
  double norm2 = 0.0;
  for (float& q : p.rotation) {
    q = r.f32();
    norm2 += static_cast<double>(q) * q;
  }
  bad = bad || !std::isfinite(p.position.x) || !std::isfinite(p.position.y) ||
        !std::isfinite(p.position.z) || !std::isfinite(norm2) || norm2 < 0.25 || norm2 > 4.0;
  return p;
}

bool read_bool(ByteReader& r, bool& bad) {
  const std::uint8_t v = r.u8();
  bad = bad || v > 1;
  return v == 1;
}

template <std::size_t N>
void write_bytes(ByteWriter& w, const std::array<std::uint8_t, N>& bytes) {
  for (const std::uint8_t b : bytes) w.u8(b);
}

template <std::size_t N>
void read_bytes(ByteReader& r, std::array<std::uint8_t, N>& bytes) {
  for (std::uint8_t& b : bytes) b = r.u8();
}

void write_stroke(ByteWriter& w, const StrokeBegin& s) {
  w.u32(s.stroke);
  w.u32(s.mesh_version);
  w.u8(s.method);
  w.u8(s.hand_mask);
  w.f64(s.radius_m);
  for (std::size_t h = 0; h < kLinkHands; ++h) {
    if ((s.hand_mask & (1u << h)) != 0) write_pose(w, s.start[h]);
  }
  w.f32(s.refine_threshold_m);
  write_bytes(w, s.symmetry);
}

// The group's bytes in canonical form (none included), as journal records check them.
bool valid_symmetry(const std::array<std::uint8_t, 4>& b) {
  switch (b[0]) {
    case 0:
      return b[1] == 0 && b[2] == 0 && b[3] == 0;
    case 1:
      return b[1] >= 1 && b[1] <= 7 && b[2] == 0 && b[3] == 0;
    case 2:
    case 3:
      return b[1] == 0 && b[2] <= 2 && b[3] >= 2 && b[3] <= 12;
    default:
      return false;
  }
}

bool read_stroke(ByteReader& r, StrokeBegin& s) {
  bool bad = false;
  s.stroke = r.u32();
  s.mesh_version = r.u32();
  s.method = r.u8();
  s.hand_mask = r.u8();
  s.radius_m = r.f64();
  if (s.method > 2 || s.hand_mask == 0 || s.hand_mask > 3) return false;
  bad = !std::isfinite(s.radius_m) || !(s.radius_m > 0.0);
  for (std::size_t h = 0; h < kLinkHands; ++h) {
    s.start[h] = (s.hand_mask & (1u << h)) != 0 ? read_pose(r, bad) : Pose{};
  }
  s.refine_threshold_m = r.f32();
  read_bytes(r, s.symmetry);
  return !bad && std::isfinite(s.refine_threshold_m) && s.refine_threshold_m >= 0.0F &&
         valid_symmetry(s.symmetry);
}

void write_hands(ByteWriter& w, const Hands& l) {
  w.u16(l.sequence);
  w.u16(l.stroke);
  w.u8(l.flags);
  w.u8(l.buttons);
  w.f32(l.radius_m);
  for (std::size_t h = 0; h < kLinkHands; ++h) {
    if ((l.flags & (kHandSample0 << h)) != 0) write_compact(w, l.hands[h]);
  }
}

bool read_hands(ByteReader& r, Hands& l) {
  bool bad = false;
  l.sequence = r.u16();
  l.stroke = r.u16();
  l.flags = r.u8();
  l.buttons = r.u8();
  l.radius_m = r.f32();
  if ((l.flags & ~kHandsFlagMask) != 0) return false;
  bad = !std::isfinite(l.radius_m) || l.radius_m < 0.0F;
  for (std::size_t h = 0; h < kLinkHands; ++h) {
    l.hands[h] = (l.flags & (kHandSample0 << h)) != 0 ? read_compact(r, bad) : CompactPose{};
  }
  return !bad;
}

void write_status(ByteWriter& w, const StatusReport& s) {
  w.u32(s.mesh_version);
  w.u32(s.vertex_count);
  w.u32(s.vertex_capacity);
  w.u32(s.triangle_count);
  w.u32(s.triangle_capacity);
  w.u8(s.tracker_state);
  w.u8(s.buttons_state);
  w.f32(s.tracker_rate_hz);
  w.u8(s.method);
  w.u8(s.clutch);
  w.f32(s.turned_rad);
  w.f32(s.turn_limit_rad);
  w.u64(s.strokes.committed);
  w.u64(s.strokes.not_saved);
  w.u64(s.strokes.capacity_stops);
  w.u64(s.traffic.live_sent);
  w.u64(s.traffic.live_dropped);
  w.u64(s.traffic.frames_rejected);
  write_bytes(w, s.symmetry);
  w.u8(s.spectators);
}

bool read_workspace(ByteReader& r, Workspace& s) {
  s.flags = r.u8();
  bool good = (s.flags & ~kWorkspaceFlagMask) == 0;
  for (glm::vec3* v : {&s.up, &s.min, &s.max}) {
    *v = {r.f32(), r.f32(), r.f32()};
    good = good && std::isfinite(v->x) && std::isfinite(v->y) && std::isfinite(v->z);
  }
  return good;
}

bool read_status(ByteReader& r, StatusReport& s) {
  s.mesh_version = r.u32();
  s.vertex_count = r.u32();
  s.vertex_capacity = r.u32();
  s.triangle_count = r.u32();
  s.triangle_capacity = r.u32();
  s.tracker_state = r.u8();
  s.buttons_state = r.u8();
  s.tracker_rate_hz = r.f32();
  s.method = r.u8();
  s.clutch = r.u8();
  s.turned_rad = r.f32();
  s.turn_limit_rad = r.f32();
  s.strokes.committed = r.u64();
  s.strokes.not_saved = r.u64();
  s.strokes.capacity_stops = r.u64();
  s.traffic.live_sent = r.u64();
  s.traffic.live_dropped = r.u64();
  s.traffic.frames_rejected = r.u64();
  read_bytes(r, s.symmetry);
  s.spectators = r.u8();
  return s.tracker_state <= 2 && s.buttons_state <= 1 && s.method <= 2 && s.clutch <= 3 &&
         std::isfinite(s.tracker_rate_hz) && std::isfinite(s.turned_rad) &&
         std::isfinite(s.turn_limit_rad) && valid_symmetry(s.symmetry);
}

void write_visitor(ByteWriter& w, const VisitorState& v) {
  w.u8(static_cast<std::uint8_t>(v.phase));
  w.u8(v.flags);
  w.u32(v.visitor);
  w.u32(v.sculpture);
  w.u32(v.strokes);
  w.f32(v.idle_left_s);
  w.f32(v.grace_left_s);
}

bool read_visitor(ByteReader& r, VisitorState& v) {
  const std::uint8_t phase = r.u8();
  v.phase = static_cast<VisitorPhase>(phase);
  v.flags = r.u8();
  v.visitor = r.u32();
  v.sculpture = r.u32();
  v.strokes = r.u32();
  v.idle_left_s = r.f32();
  v.grace_left_s = r.f32();
  return phase <= kLastVisitorPhase && (v.flags & ~kVisitorFlagMask) == 0 &&
         std::isfinite(v.idle_left_s) && v.idle_left_s >= 0.0F && std::isfinite(v.grace_left_s) &&
         v.grace_left_s >= 0.0F;
}

bool read_vertices(ByteReader& r, Vertices& v) {
  v.count = r.u16();
  if (v.count > kMaxVerticesPerChunk) return false;
  bool bad = false;
  for (std::size_t i = 0; i < v.count; ++i) {
    VertexEntry& e = v.items[i];
    e.index = r.u32();
    e.x = r.f32();
    e.y = r.f32();
    e.z = r.f32();
    bad = bad || !std::isfinite(e.x) || !std::isfinite(e.y) || !std::isfinite(e.z);
  }
  return !bad;
}

bool read_triangles(ByteReader& r, Triangles& t) {
  t.first = r.u32();
  t.count = r.u16();
  if (t.count > kMaxTrianglesPerChunk) return false;
  for (std::size_t i = 0; i < std::size_t{3} * t.count; ++i) t.indices[i] = r.u32();
  return true;
}

bool read_hello(ByteReader& r, Hello& h) {
  const std::uint8_t role = r.u8();
  h.role = static_cast<Role>(role);
  h.flags = r.u8();
  h.mesh_version = r.u32();
  h.mesh_checksum = r.u64();
  read_bytes(r, h.nonce);
  return (role == static_cast<std::uint8_t>(Role::station) ||
          role == static_cast<std::uint8_t>(Role::bridge)) &&
         (h.flags & ~kHelloFlagMask) == 0;
}

template <class T>
T& reset_as(LinkMessage& m) {
  // A decoder's message is reused: only a change of type constructs anew.
  if (T* same = std::get_if<T>(&m)) return *same;
  return m.emplace<T>();
}

}  // namespace

bool write_body(ByteWriter& w, const Hello& m) {
  w.u8(static_cast<std::uint8_t>(m.role));
  w.u8(m.flags);
  w.u32(m.mesh_version);
  w.u64(m.mesh_checksum);
  write_bytes(w, m.nonce);
  return true;
}

bool write_body(ByteWriter& w, const Auth& m) {
  write_bytes(w, m.tag);
  return true;
}

bool write_body(ByteWriter& w, const Bye& m) {
  w.u8(static_cast<std::uint8_t>(m.reason));
  return true;
}

bool write_body(ByteWriter& w, const MeshBegin& m) {
  w.u8(m.full ? 1 : 0);
  w.u32(m.base_version);
  w.u32(m.version);
  w.u32(m.vertex_count);
  w.u32(m.triangle_count);
  return true;
}

bool write_body(ByteWriter& w, const Vertices& m) {
  if (m.count > kMaxVerticesPerChunk) return false;
  w.u16(m.count);
  for (std::size_t i = 0; i < m.count; ++i) {
    const VertexEntry& v = m.items[i];
    w.u32(v.index);
    w.f32(v.x);
    w.f32(v.y);
    w.f32(v.z);
  }
  return true;
}

bool write_body(ByteWriter& w, const Triangles& m) {
  if (m.count > kMaxTrianglesPerChunk) return false;
  w.u32(m.first);
  w.u16(m.count);
  for (std::size_t i = 0; i < std::size_t{3} * m.count; ++i) w.u32(m.indices[i]);
  return true;
}

bool write_body(ByteWriter& w, const MeshEnd& m) {
  w.u32(m.version);
  w.u64(m.checksum);
  return true;
}

bool write_body(ByteWriter& w, const ResendRequest& m) {
  w.u32(m.have_version);
  w.u64(m.have_checksum);
  return true;
}

bool write_body(ByteWriter& w, const StrokeBegin& m) {
  if (m.method > 2 || m.hand_mask == 0 || m.hand_mask > 3) return false;
  write_stroke(w, m);
  return true;
}

bool write_body(ByteWriter& w, const Hands& m) {
  if ((m.flags & ~kHandsFlagMask) != 0) return false;
  write_hands(w, m);
  return true;
}

bool write_body(ByteWriter& w, const ObjectPose& m) {
  write_compact(w, m.pose);
  return true;
}

bool write_body(ByteWriter& w, const StatusReport& m) {
  if (!valid_symmetry(m.symmetry)) return false;
  write_status(w, m);
  return true;
}

bool write_body(ByteWriter& w, const VisitorState& m) {
  if (static_cast<std::uint8_t>(m.phase) > kLastVisitorPhase ||
      (m.flags & ~kVisitorFlagMask) != 0) {
    return false;
  }
  write_visitor(w, m);
  return true;
}

bool write_body(ByteWriter& w, const Notice& m) {
  w.u8(static_cast<std::uint8_t>(m.code));
  w.u8(m.detail);
  return true;
}

bool write_body(ByteWriter& w, const Workspace& m) {
  if ((m.flags & ~kWorkspaceFlagMask) != 0) return false;
  w.u8(m.flags);
  for (const glm::vec3& v : {m.up, m.min, m.max}) {
    w.f32(v.x);
    w.f32(v.y);
    w.f32(v.z);
  }
  return true;
}

bool write_body(ByteWriter& w, const Command& m) {
  w.u8(static_cast<std::uint8_t>(m.kind));
  w.u8(m.method);
  return true;
}

namespace {

bool read_small(ByteReader& r, MessageType type, LinkMessage& m) {
  switch (type) {
    case MessageType::auth:
      read_bytes(r, reset_as<Auth>(m).tag);
      return true;
    case MessageType::bye: {
      const std::uint8_t reason = r.u8();
      reset_as<Bye>(m).reason = static_cast<ByeReason>(reason);
      return reason >= 1 && reason <= kLastByeReason;
    }
    case MessageType::mesh_begin: {
      bool bad = false;
      MeshBegin& b = reset_as<MeshBegin>(m);
      b.full = read_bool(r, bad);
      b.base_version = r.u32();
      b.version = r.u32();
      b.vertex_count = r.u32();
      b.triangle_count = r.u32();
      return !bad;
    }
    case MessageType::mesh_end: {
      MeshEnd& e = reset_as<MeshEnd>(m);
      e.version = r.u32();
      e.checksum = r.u64();
      return true;
    }
    case MessageType::resend_request: {
      ResendRequest& q = reset_as<ResendRequest>(m);
      q.have_version = r.u32();
      q.have_checksum = r.u64();
      return true;
    }
    case MessageType::command: {
      Command& c = reset_as<Command>(m);
      const std::uint8_t kind = r.u8();
      c.kind = static_cast<CommandKind>(kind);
      c.method = r.u8();
      return kind >= 1 && kind <= kLastCommandKind && c.method <= 2;
    }
    case MessageType::notice: {
      Notice& n = reset_as<Notice>(m);
      const std::uint8_t code = r.u8();
      n.code = static_cast<NoticeCode>(code);
      n.detail = r.u8();
      return code >= 1 && code <= kLastNoticeCode;
    }
    default:
      return false;
  }
}

}  // namespace

bool read_body(ByteReader& r, MessageType type, LinkMessage& m) {
  bool good = true;
  switch (type) {
    case MessageType::hello:
      good = read_hello(r, reset_as<Hello>(m));
      break;
    case MessageType::vertices:
      good = read_vertices(r, reset_as<Vertices>(m));
      break;
    case MessageType::triangles:
      good = read_triangles(r, reset_as<Triangles>(m));
      break;
    case MessageType::stroke:
      good = read_stroke(r, reset_as<StrokeBegin>(m));
      break;
    case MessageType::hands:
      good = read_hands(r, reset_as<Hands>(m));
      break;
    case MessageType::object: {
      bool bad = false;
      reset_as<ObjectPose>(m).pose = read_compact(r, bad);
      good = !bad;
      break;
    }
    case MessageType::status:
      good = read_status(r, reset_as<StatusReport>(m));
      break;
    case MessageType::workspace:
      good = read_workspace(r, reset_as<Workspace>(m));
      break;
    case MessageType::visitor:
      good = read_visitor(r, reset_as<VisitorState>(m));
      break;
    default:
      good = read_small(r, type, m);
      break;
  }
  return good && r.ok() && r.at_end();
}

}  // namespace twister::link::internal
