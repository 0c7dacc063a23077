// Session checkpoints: a snapshot of everything a journal replay builds (the mesh's
// vertex positions, counts and triangles, the undo history with the topology of
// refined commits, object pose, next sequence) at a record boundary of the journal,
// so start-up restores it and replays only the records after it instead of the whole
// history. The journal itself is never cut: it continues after the checkpoint and
// stays the complete history (`twister replay` still uses all of it).
//
// File, format version 2 (little-endian; docs/reliability.md "Checkpoints"):
//   header (kCheckpointHeaderBytes): "TWCK", u32 version, u64 journal_offset, u64
//     journal_records, u32 next_sequence, u32 last_record_crc, u64 base_checksum, u32
//     vertex_count, u32 triangle_count (the mesh's now), u64 vertex_capacity, u64
//     triangle_capacity (the mesh's), u64 change_capacity, u64 entry_capacity, u64
//     entry_count, u64 undo_count, u64 used_changes, u64 dropped, u64
//     triangle_change_capacity, u64 used_triangle_changes, object pose (12 f64:
//     origin, U, V, W)
//   x[vertex_count], y[...], z[...] as f32
//   triangles[triangle_count]: u32 x 3 (each < vertex_count)
//   entry_count undo entries (kCheckpointEntryBytes): u64 first_change, u64
//     change_count, u64 first_triangle_change, u64 triangle_change_count, u32
//     vertices_before, u32 vertices_after, u32 triangles_before, u32 triangles_after,
//     u8 object_move, u8 topology, 6 zero bytes, object before and after (12 f64 each)
//   used_changes vertex changes: u32 index, before xyz f32, after xyz f32
//   used_triangle_changes triangle changes: u32 index, before u32 x 3, after u32 x 3
//   u32 CRC-32 of everything before it.
// Version 1 (no triangles, no topology) is refused as data_loss: start-up then
// replays the whole journal, as for any checkpoint that does not fit.
// Every value is checked before it is used: finite positions and poses, indices
// within the counts, counts within the capacities, entries packed and contiguous in
// both change pools, and the history's counts chained: a refined entry starts from
// the counts the entries before it leave and the mesh holds the counts the undoable
// entries end at; a refined entry's triangle changes are its rewritten triangles
// (index < triangles_before) then every appended one in order, and its vertex and
// triangle indices fit the counts before and after it. What only a replay of the
// history could show (a mesh triangle on a vertex that an undoable refined entry added
// without writing that triangle) UndoHistory::undo() refuses when that entry is undone.
// A checkpoint fits a journal when the record ending at journal_offset has the CRC
// field last_record_crc and journal_records records precede it, and fits a model
// when base_checksum is the initial model's checksum (the caller's check: Station)
// and the mesh and history capacities match; otherwise start-up ignores it and
// replays the whole journal.
//
// CheckpointWriter writes one incrementally (a budget of bytes per call, so the
// station's loop never stalls on a large mesh) through a FileSink (atomic: a crash
// leaves the previous checkpoint); the session must not change while it writes (the
// caller aborts when next_sequence() moves). No allocation; not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/math/frame.hpp"
#include "twister/ports/file_sink.hpp"
#include "twister/ports/storage.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::checkpoint {

inline constexpr std::array<std::byte, 4> kCheckpointMagic{std::byte{'T'}, std::byte{'W'},
                                                           std::byte{'C'}, std::byte{'K'}};
inline constexpr std::uint32_t kCheckpointVersion = 2;
inline constexpr std::size_t kCheckpointHeaderBytes = 224;
inline constexpr std::size_t kCheckpointEntryBytes = 4 * 8 + 4 * 4 + 8 + 2 * 12 * 8;
inline constexpr std::size_t kCheckpointChangeBytes = 4 + 6 * 4;
inline constexpr std::size_t kCheckpointTriangleBytes = std::size_t{3} * 4;
inline constexpr std::size_t kCheckpointTriangleChangeBytes = 4 + 6 * 4;

struct CheckpointHeader {
  std::uint64_t journal_offset = 0;   // end of the last record it includes
  std::uint64_t journal_records = 0;  // records it includes
  std::uint32_t next_sequence = 0;
  std::uint32_t last_record_crc = 0;  // CRC field of the record ending at journal_offset
  std::uint64_t base_checksum = 0;    // the initial model's mesh checksum
  std::uint32_t vertex_count = 0;     // the mesh's counts now
  std::uint32_t triangle_count = 0;
  std::uint64_t vertex_capacity = 0;  // the mesh's capacities
  std::uint64_t triangle_capacity = 0;
  std::uint64_t change_capacity = 0;  // the undo history's sizes
  std::uint64_t entry_capacity = 0;
  std::uint64_t entry_count = 0;
  std::uint64_t undo_count = 0;
  std::uint64_t used_changes = 0;
  std::uint64_t dropped = 0;
  std::uint64_t triangle_change_capacity = 0;
  std::uint64_t used_triangle_changes = 0;
  math::Frame object{};
};

// Bytes of the whole file for this header.
std::uint64_t checkpoint_bytes(const CheckpointHeader& header);

// Where in its journal a new checkpoint stands (the journal writer's position).
struct CheckpointAnchor {
  std::uint64_t journal_offset = 0;
  std::uint64_t journal_records = 0;
  std::uint32_t last_record_crc = 0;
};

class CheckpointWriter {
 public:
  // `sink` may be null: begin() then fails with failed_precondition.
  explicit CheckpointWriter(ports::FileSink* sink) : sink_(sink) {}
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;

  // Starts a checkpoint of `session` as it stands (no stroke or move may be open:
  // failed_precondition). Errors of FileSink::begin().
  Status begin(const session::SculptSession& session, const CheckpointAnchor& anchor,
               std::uint64_t base_checksum);
  // Writes up to about `budget_bytes` more (at least one element). true: all written
  // and committed (synced, named). Errors of the sink (then aborted).
  // failed_precondition: no begin().
  Result<bool> step(const session::SculptSession& session, std::size_t budget_bytes);
  // Drops a checkpoint in progress (the previous one stays).
  void abort();

  bool active() const { return active_; }
  const CheckpointHeader& header() const { return header_; }

 private:
  // The bytes of element `index` of section `section_` into `out`; returns the size.
  std::size_t encode(const session::SculptSession& session, std::span<std::byte> out) const;
  std::uint64_t section_size() const;

  ports::FileSink* sink_;
  bool active_ = false;
  CheckpointHeader header_{};
  int section_ = 0;
  std::uint64_t index_ = 0;
  std::uint32_t crc_ = 0;
  std::array<std::byte, std::size_t{16} * 1024> chunk_{};
};

// The header of a checkpoint file. data_loss: not a checkpoint (magic, version,
// size); io_error: storage failure.
Result<CheckpointHeader> read_checkpoint_header(ports::Storage& storage);

// Checks the whole file against `session` (sizes, capacities, CRC, every value and
// the history's structure) without changing anything. data_loss: damaged or does not
// fit; io_error: storage failure. Does not compare base_checksum (the caller does).
Status verify_checkpoint(ports::Storage& storage, const CheckpointHeader& header,
                         const session::SculptSession& session);

// Writes a verified checkpoint's state into `session` (fresh: no record applied, nothing
// open): the mesh's counts, positions and triangles, the history, pose and next
// sequence. Errors as verify_checkpoint (the session is then partly written: start
// over).
Status restore_checkpoint(ports::Storage& storage, const CheckpointHeader& header,
                          session::SculptSession& session);

}  // namespace twister::checkpoint
