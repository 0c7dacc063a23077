// CheckpointWriter: the file, element by element, in the order of the format
// (header, x, y, z, triangles, undo entries, vertex changes, triangle changes, CRC),
// a chunk at a time.
#include "twister/checkpoint/session_checkpoint.hpp"

#include <span>

#include "checkpoint_format.hpp"
#include "twister/base/checksum.hpp"
#include "twister/base/internal/byte_cursor.hpp"

namespace twister::checkpoint {
namespace {

enum Section : int {
  kHeader = 0,
  kX,
  kY,
  kZ,
  kTriangles,
  kEntries,
  kChanges,
  kTriangleChanges,
  kCrc,
  kDone
};

}  // namespace

std::uint64_t checkpoint_bytes(const CheckpointHeader& h) {
  return kCheckpointHeaderBytes + std::uint64_t{12} * h.vertex_count +
         std::uint64_t{kCheckpointTriangleBytes} * h.triangle_count +
         kCheckpointEntryBytes * h.entry_count + kCheckpointChangeBytes * h.used_changes +
         kCheckpointTriangleChangeBytes * h.used_triangle_changes + 4;
}

Status CheckpointWriter::begin(const session::SculptSession& session,
                               const CheckpointAnchor& anchor, std::uint64_t base_checksum) {
  abort();
  if (sink_ == nullptr || session.busy()) return StatusCode::failed_precondition;
  const session::UndoHistory& history = session.history();
  const mesh::Mesh& m = session.mesh();
  CheckpointHeader& h = header_;
  h = {};
  h.journal_offset = anchor.journal_offset;
  h.journal_records = anchor.journal_records;
  h.last_record_crc = anchor.last_record_crc;
  h.next_sequence = session.next_sequence();
  h.base_checksum = base_checksum;
  h.vertex_count = static_cast<std::uint32_t>(m.vertex_count());
  h.triangle_count = static_cast<std::uint32_t>(m.triangle_count());
  h.vertex_capacity = m.vertex_capacity();
  h.triangle_capacity = m.triangle_capacity();
  h.change_capacity = history.change_capacity();
  h.entry_capacity = history.entry_capacity();
  h.entry_count = history.entries().size();
  h.undo_count = history.undo_depth();
  h.used_changes = history.changes().size();
  h.dropped = history.dropped_entries();
  h.triangle_change_capacity = history.triangle_change_capacity();
  h.used_triangle_changes = history.triangle_changes().size();
  h.object = session.object_pose();
  TWISTER_TRY(sink_->begin());
  active_ = true;
  section_ = kHeader;
  index_ = 0;
  crc_ = 0;
  return ok_status();
}

std::uint64_t CheckpointWriter::section_size() const {
  switch (section_) {
    case kHeader:
      return 1;
    case kX:
    case kY:
    case kZ:
      return header_.vertex_count;
    case kTriangles:
      return header_.triangle_count;
    case kEntries:
      return header_.entry_count;
    case kChanges:
      return header_.used_changes;
    case kTriangleChanges:
      return header_.used_triangle_changes;
    default:
      return 0;
  }
}

std::size_t CheckpointWriter::encode(const session::SculptSession& session,
                                     std::span<std::byte> out) const {
  namespace f = format;
  const auto i = static_cast<std::size_t>(index_);
  const mesh::Mesh& m = session.mesh();
  switch (section_) {
    case kHeader:
      f::encode_header(header_, out);
      return kCheckpointHeaderBytes;
    case kX:
    case kY:
    case kZ: {
      const std::span<const float> axis = section_ == kX ? m.x() : section_ == kY ? m.y() : m.z();
      twister::internal::ByteWriter(out.first(4)).f32(axis[i]);
      return 4;
    }
    case kTriangles:
      f::encode_triangle(m.triangle(static_cast<std::uint32_t>(i)), out);
      return kCheckpointTriangleBytes;
    case kEntries:
      f::encode_entry(session.history().entries()[i], out);
      return kCheckpointEntryBytes;
    case kChanges:
      f::encode_change(session.history().changes()[i], out);
      return kCheckpointChangeBytes;
    case kTriangleChanges:
      f::encode_triangle_change(session.history().triangle_changes()[i], out);
      return kCheckpointTriangleChangeBytes;
    default:
      return 0;
  }
}

Result<bool> CheckpointWriter::step(const session::SculptSession& session,
                                    std::size_t budget_bytes) {
  if (!active_) return StatusCode::failed_precondition;
  std::size_t written = 0;
  while (section_ != kDone) {
    std::size_t fill = 0;
    while (section_ < kCrc && fill + format::kMaxElementBytes <= chunk_.size()) {
      if (index_ == section_size()) {
        ++section_;
        index_ = 0;
        continue;
      }
      fill += encode(session, std::span(chunk_).subspan(fill));
      ++index_;
    }
    crc_ = crc32(std::span<const std::byte>(chunk_).first(fill), crc_);
    if (section_ == kCrc) {
      twister::internal::ByteWriter(std::span(chunk_).subspan(fill, 4)).u32(crc_);
      fill += 4;
      section_ = kDone;
    }
    if (const Status s = sink_->write(std::span<const std::byte>(chunk_).first(fill)); !s.ok()) {
      abort();
      return s;
    }
    written += fill;
    if (written >= budget_bytes) break;
  }
  if (section_ != kDone) return false;
  active_ = false;
  TWISTER_TRY(sink_->commit());
  return true;
}

void CheckpointWriter::abort() {
  if (active_) sink_->abort();
  active_ = false;
}

}  // namespace twister::checkpoint
