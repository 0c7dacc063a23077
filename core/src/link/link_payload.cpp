// Message bodies: one write_* / read_* pair per message type, same field order.
#include "link_payload.hpp"

#include <cmath>

namespace twister::link::internal {
namespace {

void write_frame(ByteWriter& w, const Pose& f) {
  w.vec(f.origin);
  w.vec(f.u);
  w.vec(f.v);
  w.vec(f.w);
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A frame or screw with NaN/inf would poison the display's shader: refused here.
Pose read_frame(ByteReader& r, bool& bad) {
  Pose f;
  f.origin = r.vec();
  f.u = r.vec();
  f.v = r.vec();
  f.w = r.vec();
  bad = bad || !finite(f.origin) || !finite(f.u) || !finite(f.v) || !finite(f.w);
  return f;
}

void write_screw(ByteWriter& w, const Screw& s) {
  w.vec(s.axis);
  w.f64(s.angle);
  w.f64(s.slide);
  w.vec(s.mid);
  w.vec(s.chord);
  w.f64(s.cot_half);
  w.u8(s.pure_translation ? 1 : 0);
}

Screw read_screw(ByteReader& r, bool& bad) {
  Screw s;
  s.axis = r.vec();
  s.angle = r.f64();
  s.slide = r.f64();
  s.mid = r.vec();
  s.chord = r.vec();
  s.cot_half = r.f64();
  const std::uint8_t pure = r.u8();
  bad = bad || pure > 1 || !finite(s.axis) || !std::isfinite(s.angle) || !std::isfinite(s.slide) ||
        !finite(s.mid) || !finite(s.chord) || !std::isfinite(s.cot_half);
  s.pure_translation = pure == 1;
  return s;
}

bool read_bool(ByteReader& r, bool& bad) {
  const std::uint8_t v = r.u8();
  bad = bad || v > 1;
  return v == 1;
}

}  // namespace

bool write_body(ByteWriter& w, const LinkMessage& m) {
  switch (m.type) {
    case MessageType::hello:
      w.u8(static_cast<std::uint8_t>(m.hello.role));
      w.u32(m.hello.mesh_version);
      w.u64(m.hello.mesh_checksum);
      return true;
    case MessageType::mesh_begin:
      w.u8(m.mesh_begin.full ? 1 : 0);
      w.u32(m.mesh_begin.base_version);
      w.u32(m.mesh_begin.version);
      w.u32(m.mesh_begin.vertex_count);
      w.u32(m.mesh_begin.triangle_count);
      return true;
    case MessageType::vertices:
      if (m.vertices.count > kMaxVerticesPerChunk) return false;
      w.u16(m.vertices.count);
      for (std::size_t i = 0; i < m.vertices.count; ++i) {
        const VertexEntry& v = m.vertices.items[i];
        w.u32(v.index);
        w.f32(v.x);
        w.f32(v.y);
        w.f32(v.z);
      }
      return true;
    case MessageType::triangles:
      if (m.triangles.count > kMaxTrianglesPerChunk) return false;
      w.u32(m.triangles.first);
      w.u16(m.triangles.count);
      for (std::size_t i = 0; i < std::size_t{3} * m.triangles.count; ++i)
        w.u32(m.triangles.indices[i]);
      return true;
    case MessageType::mesh_end:
      w.u32(m.mesh_end.version);
      w.u64(m.mesh_end.checksum);
      return true;
    case MessageType::live_warp: {
      const LiveWarp& l = m.live_warp;
      if (l.hand_mask > 3 || l.method > 2) return false;
      w.u32(l.mesh_version);
      w.u32(l.stroke);
      w.u8(l.active ? 1 : 0);
      w.u8(l.method);
      w.u8(l.hand_mask);
      w.f64(l.radius_m);
      for (std::size_t h = 0; h < kLinkHands; ++h) {
        if ((l.hand_mask & (1u << h)) == 0) continue;  // only the hands in use
        write_frame(w, l.hands[h].start);
        write_frame(w, l.hands[h].end);
        write_screw(w, l.hands[h].screw);
      }
      return true;
    }
    case MessageType::resend_request:
      w.u32(m.resend_request.have_version);
      w.u64(m.resend_request.have_checksum);
      return true;
    case MessageType::status: {
      const StatusReport& s = m.status;
      w.u32(s.mesh_version);
      w.u64(s.strokes_committed);
      w.u64(s.live_sent);
      w.u64(s.live_dropped);
      w.u64(s.full_sends);
      w.u64(s.commits_sent);
      w.u64(s.frames_rejected);
      return true;
    }
  }
  return false;
}

bool read_body(ByteReader& r, LinkMessage& m) {
  bool bad = false;
  switch (m.type) {
    case MessageType::hello: {
      const std::uint8_t role = r.u8();
      bad = role != static_cast<std::uint8_t>(Role::station) &&
            role != static_cast<std::uint8_t>(Role::bridge);
      m.hello.role = static_cast<Role>(role);
      m.hello.mesh_version = r.u32();
      m.hello.mesh_checksum = r.u64();
      break;
    }
    case MessageType::mesh_begin:
      m.mesh_begin.full = read_bool(r, bad);
      m.mesh_begin.base_version = r.u32();
      m.mesh_begin.version = r.u32();
      m.mesh_begin.vertex_count = r.u32();
      m.mesh_begin.triangle_count = r.u32();
      break;
    case MessageType::vertices:
      m.vertices.count = r.u16();
      if (m.vertices.count > kMaxVerticesPerChunk) return false;
      for (std::size_t i = 0; i < m.vertices.count; ++i) {
        VertexEntry& v = m.vertices.items[i];
        v.index = r.u32();
        v.x = r.f32();
        v.y = r.f32();
        v.z = r.f32();
        bad = bad || !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z);
      }
      break;
    case MessageType::triangles:
      m.triangles.first = r.u32();
      m.triangles.count = r.u16();
      if (m.triangles.count > kMaxTrianglesPerChunk) return false;
      for (std::size_t i = 0; i < std::size_t{3} * m.triangles.count; ++i)
        m.triangles.indices[i] = r.u32();
      break;
    case MessageType::mesh_end:
      m.mesh_end.version = r.u32();
      m.mesh_end.checksum = r.u64();
      break;
    case MessageType::live_warp: {
      LiveWarp& l = m.live_warp;
      l.mesh_version = r.u32();
      l.stroke = r.u32();
      l.active = read_bool(r, bad);
      l.method = r.u8();
      l.hand_mask = r.u8();
      l.radius_m = r.f64();
      if (l.hand_mask > 3 || l.method > 2) return false;
      bad = bad || !std::isfinite(l.radius_m);
      for (std::size_t h = 0; h < kLinkHands; ++h) {
        if ((l.hand_mask & (1u << h)) == 0) {
          l.hands[h] = LiveHand{};
          continue;
        }
        l.hands[h].start = read_frame(r, bad);
        l.hands[h].end = read_frame(r, bad);
        l.hands[h].screw = read_screw(r, bad);
      }
      break;
    }
    case MessageType::resend_request:
      m.resend_request.have_version = r.u32();
      m.resend_request.have_checksum = r.u64();
      break;
    case MessageType::status:
      m.status.mesh_version = r.u32();
      m.status.strokes_committed = r.u64();
      m.status.live_sent = r.u64();
      m.status.live_dropped = r.u64();
      m.status.full_sends = r.u64();
      m.status.commits_sent = r.u64();
      m.status.frames_rejected = r.u64();
      break;
    default:
      return false;
  }
  return !bad && r.ok() && r.at_end();
}

}  // namespace twister::link::internal
