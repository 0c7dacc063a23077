// Checkpoint reading: one walk over the file that either only checks it (verify) or
// also writes it into the session (restore). The file is read through a 16 KiB
// window; every value is checked before it is used (the history's sections:
// checkpoint_history.cpp).
#include <array>
#include <cmath>
#include <span>

#include "checkpoint_format.hpp"
#include "checkpoint_input.hpp"
#include "twister/base/checksum.hpp"
#include "twister/base/internal/byte_cursor.hpp"
#include "twister/checkpoint/session_checkpoint.hpp"

namespace twister::checkpoint {
namespace format {

bool Input::take(std::size_t n, std::span<const std::byte>& out) {
  if (pos_ + n > size_) {
    const std::size_t keep = size_ - pos_;
    for (std::size_t i = 0; i < keep; ++i) window_[i] = window_[pos_ + i];
    size_ = keep;
    pos_ = 0;
    while (size_ < window_.size()) {
      const auto got = storage_.read_at(offset_ + size_, window_.subspan(size_));
      if (!got.ok() || *got == 0) break;
      size_ += *got;
    }
    if (size_ < n) return false;
  }
  out = std::span<const std::byte>(window_).subspan(pos_, n);
  crc_ = crc32(out, crc_);
  pos_ += n;
  offset_ += n;
  return true;
}

}  // namespace format

namespace {

using format::Input;

// The capacities are the session's and the counts within them (the model itself is
// identified by base_checksum, which the caller compares).
bool fits(const CheckpointHeader& h, const session::SculptSession& session) {
  const session::UndoHistory& history = session.history();
  const mesh::Mesh& m = session.mesh();
  return h.vertex_capacity == m.vertex_capacity() && h.triangle_capacity == m.triangle_capacity() &&
         h.vertex_count <= h.vertex_capacity && h.triangle_count <= h.triangle_capacity &&
         h.change_capacity == history.change_capacity() &&
         h.entry_capacity == history.entry_capacity() &&
         h.triangle_change_capacity == history.triangle_change_capacity() &&
         h.entry_count <= h.entry_capacity && h.undo_count <= h.entry_count &&
         h.used_changes <= h.change_capacity &&
         h.used_triangle_changes <= h.triangle_change_capacity && math::is_orthonormal(h.object);
}

// Positions and triangles; with `target`, its mesh is first resized to the counts.
Status walk_mesh(Input& in, const CheckpointHeader& h, session::SculptSession* target) {
  mesh::Mesh* m = target != nullptr ? &target->restore_target().mesh : nullptr;
  if (m != nullptr && !m->resize(h.vertex_count, h.triangle_count).ok()) {
    return StatusCode::data_loss;
  }
  std::span<const std::byte> bytes;
  for (int axis = 0; axis < 3; ++axis) {
    std::span<float> column;
    if (m != nullptr) column = axis == 0 ? m->x() : axis == 1 ? m->y() : m->z();
    for (std::uint32_t i = 0; i < h.vertex_count; ++i) {
      if (!in.take(4, bytes)) return StatusCode::data_loss;
      const float v = twister::internal::ByteReader(bytes).f32();
      if (!std::isfinite(v)) return StatusCode::data_loss;
      if (m != nullptr) column[i] = v;
    }
  }
  for (std::uint32_t t = 0; t < h.triangle_count; ++t) {
    if (!in.take(kCheckpointTriangleBytes, bytes)) return StatusCode::data_loss;
    const std::array<std::uint32_t, 3> v = format::decode_triangle(bytes);
    if (v[0] >= h.vertex_count || v[1] >= h.vertex_count || v[2] >= h.vertex_count) {
      return StatusCode::data_loss;
    }
    if (m != nullptr) m->set_triangle(t, v);
  }
  return ok_status();
}

// Checks (and with `target`, restores) the whole file.
Status walk(ports::Storage& storage, const CheckpointHeader& h,
            const session::SculptSession& session, session::SculptSession* target) {
  if (!fits(h, session)) return StatusCode::data_loss;
  TWISTER_TRY_ASSIGN(const std::uint64_t size, storage.size());
  if (size != checkpoint_bytes(h)) return StatusCode::data_loss;
  std::array<std::byte, std::size_t{16} * 1024> window{};
  Input in(storage, window);
  std::span<const std::byte> bytes;
  if (!in.take(kCheckpointHeaderBytes, bytes)) return StatusCode::data_loss;
  TWISTER_TRY(walk_mesh(in, h, target));
  TWISTER_TRY(format::walk_history(in, storage, h, target));
  const std::uint32_t crc = in.crc();
  if (!in.take(4, bytes) || twister::internal::ByteReader(bytes).u32() != crc) {
    return StatusCode::data_loss;
  }
  if (target == nullptr) return ok_status();
  session::SculptSession::RestoreTarget t = target->restore_target();
  TWISTER_TRY(t.history.adopt(static_cast<std::size_t>(h.entry_count),
                              static_cast<std::size_t>(h.undo_count),
                              static_cast<std::size_t>(h.dropped)));
  t.poses.set_object(h.object);
  t.commits.resume_after(h.next_sequence - 1);  // wraps to 0 for a checkpoint of nothing
  target->checkpoint_restored();
  return ok_status();
}

}  // namespace

Result<CheckpointHeader> read_checkpoint_header(ports::Storage& storage) {
  std::array<std::byte, kCheckpointHeaderBytes> bytes{};
  TWISTER_TRY_ASSIGN(const std::size_t n, storage.read_at(0, bytes));
  if (n != bytes.size()) return StatusCode::data_loss;
  return format::decode_header(bytes);
}

Status verify_checkpoint(ports::Storage& storage, const CheckpointHeader& header,
                         const session::SculptSession& session) {
  return walk(storage, header, session, nullptr);
}

Status restore_checkpoint(ports::Storage& storage, const CheckpointHeader& header,
                          session::SculptSession& session) {
  if (session.busy()) return StatusCode::failed_precondition;
  return walk(storage, header, session, &session);
}

}  // namespace twister::checkpoint
