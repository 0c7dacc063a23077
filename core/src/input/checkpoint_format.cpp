#include "checkpoint_format.hpp"

#include <cmath>
#include <cstring>

#include "twister/base/internal/byte_cursor.hpp"

namespace twister::input::checkpoint_format {
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
  for (const std::uint64_t v : {h.change_capacity, h.entry_capacity, h.entry_count, h.undo_count,
                                h.used_changes, h.dropped}) {
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
  h.change_capacity = r.u64();
  h.entry_capacity = r.u64();
  h.entry_count = r.u64();
  h.undo_count = r.u64();
  h.used_changes = r.u64();
  h.dropped = r.u64();
  h.object = read_frame(r);
  if (!r.ok() || !r.at_end()) return StatusCode::data_loss;
  return h;
}

void encode_entry(const UndoEntry& e, std::span<std::byte> out) {
  ByteWriter w(out.first(kCheckpointEntryBytes));
  w.u64(e.first_change);
  w.u64(e.change_count);
  w.u8(e.object_move ? 1 : 0);
  for (int i = 0; i < 7; ++i) w.u8(0);
  write_frame(w, e.object_before);
  write_frame(w, e.object_after);
}

bool decode_entry(std::span<const std::byte> in, UndoEntry& e) {
  ByteReader r(in.first(kCheckpointEntryBytes));
  e.first_change = static_cast<std::size_t>(r.u64());
  e.change_count = static_cast<std::size_t>(r.u64());
  const std::uint8_t flag = r.u8();
  bool zero = true;
  for (int i = 0; i < 7; ++i) zero = zero && r.u8() == 0;
  e.object_move = flag == 1;
  e.object_before = read_frame(r);
  e.object_after = read_frame(r);
  if (!r.ok() || flag > 1 || !zero) return false;
  return !e.object_move ||
         (math::is_orthonormal(e.object_before) && math::is_orthonormal(e.object_after));
}

void encode_change(const VertexChange& c, std::span<std::byte> out) {
  ByteWriter w(out.first(kCheckpointChangeBytes));
  w.u32(c.index);
  for (const glm::vec3& p : {c.before, c.after}) {
    w.f32(p.x);
    w.f32(p.y);
    w.f32(p.z);
  }
}

bool decode_change(std::span<const std::byte> in, VertexChange& c) {
  ByteReader r(in.first(kCheckpointChangeBytes));
  c.index = r.u32();
  c.before = read_vec3(r);
  c.after = read_vec3(r);
  return r.ok() && finite(c.before) && finite(c.after);
}

}  // namespace twister::input::checkpoint_format
