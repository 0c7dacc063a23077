#include "checkpoint_format.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include "twister/base/internal/byte_cursor.hpp"

namespace twister::checkpoint::format {
namespace {

using twister::internal::ByteReader;
using twister::internal::ByteWriter;

void write_frame(ByteWriter& w, const math::Frame& f) {
  w.vec(f.origin);
  w.vec(f.u);
  w.vec(f.v);
  w.vec(f.w);
}

math::Frame read_frame(ByteReader& r) {
  math::Frame f;
  f.origin = r.vec();
  f.u = r.vec();
  f.v = r.vec();
  f.w = r.vec();
  return f;
}

bool finite(glm::vec3 p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

glm::vec3 read_vec3(ByteReader& r) {
  const float x = r.f32();
  const float y = r.f32();
  const float z = r.f32();
  return {x, y, z};
}

}  // namespace

void encode_header(const CheckpointHeader& h, std::span<std::byte> out) {
  ByteWriter w(out.first(kCheckpointHeaderBytes));
  for (const std::byte b : kCheckpointMagic) w.u8(static_cast<std::uint8_t>(b));
  w.u32(kCheckpointVersion);
  w.u64(h.journal_offset);
  w.u64(h.journal_records);
  w.u32(h.next_sequence);
  w.u32(h.last_record_crc);
  w.u64(h.base_checksum);
  w.u32(h.vertex_count);
  w.u32(h.triangle_count);
  for (const std::uint64_t v : {h.vertex_capacity, h.triangle_capacity, h.change_capacity,
                                h.entry_capacity, h.entry_count, h.undo_count, h.used_changes,
                                h.dropped, h.triangle_change_capacity, h.used_triangle_changes}) {
    w.u64(v);
  }
  write_frame(w, h.object);
}

Result<CheckpointHeader> decode_header(std::span<const std::byte> in) {
  if (in.size() < kCheckpointHeaderBytes) return StatusCode::data_loss;
  if (std::memcmp(in.data(), kCheckpointMagic.data(), kCheckpointMagic.size()) != 0) {
    return StatusCode::data_loss;
  }
  ByteReader r(
      in.subspan(kCheckpointMagic.size(), kCheckpointHeaderBytes - kCheckpointMagic.size()));
  if (r.u32() != kCheckpointVersion) return StatusCode::data_loss;
  CheckpointHeader h;
  h.journal_offset = r.u64();
  h.journal_records = r.u64();
  h.next_sequence = r.u32();
  h.last_record_crc = r.u32();
  h.base_checksum = r.u64();
  h.vertex_count = r.u32();
  h.triangle_count = r.u32();
  for (std::uint64_t* v : {&h.vertex_capacity, &h.triangle_capacity, &h.change_capacity,
                           &h.entry_capacity, &h.entry_count, &h.undo_count, &h.used_changes,
                           &h.dropped, &h.triangle_change_capacity, &h.used_triangle_changes}) {
    *v = r.u64();
  }
  h.object = read_frame(r);
  if (!r.ok() || !r.at_end()) return StatusCode::data_loss;
  return h;
}

void encode_entry(const session::UndoEntry& e, std::span<std::byte> out) {
  ByteWriter w(out.first(kCheckpointEntryBytes));
  for (const std::size_t v :
       {e.first_change, e.change_count, e.first_triangle_change, e.triangle_change_count}) {
    w.u64(v);
  }
  for (const std::uint32_t v :
       {e.vertices_before, e.vertices_after, e.triangles_before, e.triangles_after}) {
    w.u32(v);
  }
  w.u8(e.object_move ? 1 : 0);
  w.u8(e.topology ? 1 : 0);
  for (int i = 0; i < 6; ++i) w.u8(0);
  write_frame(w, e.object_before);
  write_frame(w, e.object_after);
}

bool decode_entry(std::span<const std::byte> in, session::UndoEntry& e) {
  ByteReader r(in.first(kCheckpointEntryBytes));
  // A u64 that does not fit size_t (32-bit targets) is refused, not truncated.
  bool fits = true;
  for (std::size_t* v :
       {&e.first_change, &e.change_count, &e.first_triangle_change, &e.triangle_change_count}) {
    const std::uint64_t raw = r.u64();
    fits = fits && raw <= std::numeric_limits<std::size_t>::max();
    *v = static_cast<std::size_t>(raw);
  }
  for (std::uint32_t* v :
       {&e.vertices_before, &e.vertices_after, &e.triangles_before, &e.triangles_after}) {
    *v = r.u32();
  }
  const std::uint8_t move = r.u8();
  const std::uint8_t topology = r.u8();
  bool zero = true;
  for (int i = 0; i < 6; ++i) zero = zero && r.u8() == 0;
  e.object_move = move == 1;
  e.topology = topology == 1;
  e.object_before = read_frame(r);
  e.object_after = read_frame(r);
  if (!r.ok() || !fits || move > 1 || topology > 1 || !zero) return false;
  if (!e.topology && (e.triangle_change_count != 0 || e.vertices_before != 0 ||
                      e.vertices_after != 0 || e.triangles_before != 0 || e.triangles_after != 0)) {
    return false;
  }
  return !e.object_move ||
         (math::is_orthonormal(e.object_before) && math::is_orthonormal(e.object_after));
}

void encode_change(const session::VertexChange& c, std::span<std::byte> out) {
  ByteWriter w(out.first(kCheckpointChangeBytes));
  w.u32(c.index);
  for (const glm::vec3& p : {c.before, c.after}) {
    w.f32(p.x);
    w.f32(p.y);
    w.f32(p.z);
  }
}

bool decode_change(std::span<const std::byte> in, session::VertexChange& c) {
  ByteReader r(in.first(kCheckpointChangeBytes));
  c.index = r.u32();
  c.before = read_vec3(r);
  c.after = read_vec3(r);
  return r.ok() && finite(c.before) && finite(c.after);
}

void encode_triangle(const std::array<std::uint32_t, 3>& t, std::span<std::byte> out) {
  ByteWriter w(out.first(kCheckpointTriangleBytes));
  for (const std::uint32_t v : t) w.u32(v);
}

std::array<std::uint32_t, 3> decode_triangle(std::span<const std::byte> in) {
  ByteReader r(in.first(kCheckpointTriangleBytes));
  std::array<std::uint32_t, 3> t{};
  for (std::uint32_t& v : t) v = r.u32();
  return t;
}

void encode_triangle_change(const session::TriangleChange& c, std::span<std::byte> out) {
  ByteWriter w(out.first(kCheckpointTriangleChangeBytes));
  w.u32(c.index);
  for (const std::uint32_t v : c.before) w.u32(v);
  for (const std::uint32_t v : c.after) w.u32(v);
}

session::TriangleChange decode_triangle_change(std::span<const std::byte> in) {
  ByteReader r(in.first(kCheckpointTriangleChangeBytes));
  session::TriangleChange c;
  c.index = r.u32();
  for (std::uint32_t& v : c.before) v = r.u32();
  for (std::uint32_t& v : c.after) v = r.u32();
  return c;
}

}  // namespace twister::checkpoint::format
