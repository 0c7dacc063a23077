// Checkpoint reading: one walk over the file that either only checks it (verify) or
// also writes it into the session (restore). The file is read through a 16 KiB
// window; every value is checked before it is used.
#include <array>
#include <cmath>
#include <span>

#include "checkpoint_format.hpp"
#include "twister/base/checksum.hpp"
#include "twister/base/internal/byte_cursor.hpp"
#include "twister/input/session_checkpoint.hpp"

namespace twister::input {
namespace {

// Sequential reads through a window, with the CRC of everything taken.
class Input {
 public:
  explicit Input(ports::Storage& storage) : storage_(storage) {}
  // The next `n` bytes (n <= kMaxElementBytes). false: storage failure or the end.
  bool take(std::size_t n, std::span<const std::byte>& out) {
    if (pos_ + n > size_) {
      const std::size_t keep = size_ - pos_;
      for (std::size_t i = 0; i < keep; ++i) window_[i] = window_[pos_ + i];
      size_ = keep;
      pos_ = 0;
      while (size_ < window_.size()) {
        const auto got = storage_.read_at(offset_ + size_, std::span(window_).subspan(size_));
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
  std::uint32_t crc() const { return crc_; }

 private:
  ports::Storage& storage_;
  std::array<std::byte, std::size_t{16} * 1024> window_{};
  std::size_t pos_ = 0;
  std::size_t size_ = 0;
  std::uint64_t offset_ = 0;
  std::uint32_t crc_ = 0;
};

bool fits(const CheckpointHeader& h, const SculptSession& session) {
  const UndoHistory& history = session.history();
  return h.vertex_count == session.mesh().vertex_count() &&
         h.triangle_count == session.mesh().triangle_count() &&
         h.change_capacity == history.change_capacity() &&
         h.entry_capacity == history.entry_capacity() && h.entry_count <= h.entry_capacity &&
         h.undo_count <= h.entry_count && h.used_changes <= h.change_capacity &&
         math::is_orthonormal(h.object);
}

Status walk_positions(Input& in, const CheckpointHeader& h, SculptSession* target) {
  std::span<const std::byte> bytes;
  for (int axis = 0; axis < 3; ++axis) {
    std::span<float> column;
    if (target != nullptr) {
      mesh::Mesh& m = target->restore_target().mesh;
      column = axis == 0 ? m.x() : axis == 1 ? m.y() : m.z();
    }
    for (std::uint32_t i = 0; i < h.vertex_count; ++i) {
      if (!in.take(4, bytes)) return StatusCode::data_loss;
      const float v = twister::internal::ByteReader(bytes).f32();
      if (!std::isfinite(v)) return StatusCode::data_loss;
      if (target != nullptr) column[i] = v;
    }
  }
  return ok_status();
}

Status walk_history(Input& in, const CheckpointHeader& h, SculptSession* target) {
  std::span<const std::byte> bytes;
  std::uint64_t next_change = 0;
  for (std::uint64_t i = 0; i < h.entry_count; ++i) {
    UndoEntry e;
    if (!in.take(kCheckpointEntryBytes, bytes) || !checkpoint_format::decode_entry(bytes, e) ||
        e.first_change != next_change || e.change_count > h.used_changes - next_change) {
      return StatusCode::data_loss;
    }
    next_change += e.change_count;
    if (target != nullptr) target->restore_target().history.entry_storage()[i] = e;
  }
  if (next_change != h.used_changes) return StatusCode::data_loss;
  for (std::uint64_t i = 0; i < h.used_changes; ++i) {
    VertexChange c;
    if (!in.take(kCheckpointChangeBytes, bytes) || !checkpoint_format::decode_change(bytes, c) ||
        c.index >= h.vertex_count) {
      return StatusCode::data_loss;
    }
    if (target != nullptr) target->restore_target().history.change_storage()[i] = c;
  }
  return ok_status();
}

// Checks (and with `target`, restores) the whole file.
Status walk(ports::Storage& storage, const CheckpointHeader& h, const SculptSession& session,
            SculptSession* target) {
  if (!fits(h, session)) return StatusCode::data_loss;
  TWISTER_TRY_ASSIGN(const std::uint64_t size, storage.size());
  if (size != checkpoint_bytes(h)) return StatusCode::data_loss;
  Input in(storage);
  std::span<const std::byte> bytes;
  if (!in.take(kCheckpointHeaderBytes, bytes)) return StatusCode::data_loss;
  TWISTER_TRY(walk_positions(in, h, target));
  TWISTER_TRY(walk_history(in, h, target));
  const std::uint32_t crc = in.crc();
  if (!in.take(4, bytes) || twister::internal::ByteReader(bytes).u32() != crc) {
    return StatusCode::data_loss;
  }
  if (target == nullptr) return ok_status();
  SculptSession::RestoreTarget t = target->restore_target();
  TWISTER_TRY(t.history.adopt(static_cast<std::size_t>(h.entry_count),
                              static_cast<std::size_t>(h.undo_count),
                              static_cast<std::size_t>(h.dropped)));
  t.poses.set_object(h.object);
  t.commits.resume_after(h.next_sequence - 1);  // wraps to 0 for a checkpoint of nothing
  return ok_status();
}

}  // namespace

Result<CheckpointHeader> read_checkpoint_header(ports::Storage& storage) {
  std::array<std::byte, kCheckpointHeaderBytes> bytes{};
  TWISTER_TRY_ASSIGN(const std::size_t n, storage.read_at(0, bytes));
  if (n != bytes.size()) return StatusCode::data_loss;
  return checkpoint_format::decode_header(bytes);
}

Status verify_checkpoint(ports::Storage& storage, const CheckpointHeader& header,
                         const SculptSession& session) {
  return walk(storage, header, session, nullptr);
}

Status restore_checkpoint(ports::Storage& storage, const CheckpointHeader& header,
                          SculptSession& session) {
  if (session.busy()) return StatusCode::failed_precondition;
  return walk(storage, header, session, &session);
}

}  // namespace twister::input
