// Test harness for checkpoints of refined sessions (format version 2): writing one
// from a RefineStation, restoring it into a fresh one, comparing meshes and histories
// bit for bit, and editing a file's bytes by the layout (with the CRC made right again,
// so a structural check is what refuses the edit). Test-only (allocates).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <vector>

#include "core/session/refine_harness.hpp"
#include "fakes/fake_file_sink.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/base/checksum.hpp"
#include "twister/checkpoint/session_checkpoint.hpp"

namespace twister::checkpoint::test_support {
using namespace session::test_support;  // the session harness this one extends

using CheckpointSink = twister::test::FakeFileSinkWithStorage<std::size_t{1} << 23>;
using CheckpointFile = twister::test::FakeStorageWithStorage<std::size_t{1} << 23>;
using Bytes = std::vector<std::byte>;

// The checkpoint of `s` as it stands (anchored at its journal's end), written with
// `budget` bytes per step.
inline Bytes checkpoint_of(RefineStation& s, std::uint64_t base_checksum,
                           std::size_t budget = std::size_t{1} << 30) {
  auto sink = std::make_unique<CheckpointSink>();
  CheckpointWriter writer(sink.get());
  const CheckpointAnchor anchor{s.writer.size(), s.session->next_sequence(), s.writer.last_crc()};
  EXPECT_TRUE(writer.begin(*s.session, anchor, base_checksum).ok());
  for (int i = 0; i < 10'000'000; ++i) {
    const auto done = writer.step(*s.session, budget);
    EXPECT_TRUE(done.ok());
    if (!done.ok() || *done) break;
  }
  EXPECT_FALSE(writer.active());
  return {sink->bytes().begin(), sink->bytes().end()};
}

// verify_checkpoint of `bytes` against `s` (data_loss when the header is refused).
inline Status verify_bytes(const Bytes& bytes, RefineStation& s) {
  auto file = std::make_unique<CheckpointFile>();
  file->load(bytes);
  const auto header = read_checkpoint_header(*file);
  if (!header.ok()) return header.status();
  return verify_checkpoint(*file, *header, *s.session);
}

// Verifies, then restores `bytes` into `s`.
inline Status restore_bytes(const Bytes& bytes, RefineStation& s) {
  auto file = std::make_unique<CheckpointFile>();
  file->load(bytes);
  const auto header = read_checkpoint_header(*file);
  if (!header.ok()) return header.status();
  TWISTER_TRY(verify_checkpoint(*file, *header, *s.session));
  return restore_checkpoint(*file, *header, *s.session);
}

// Counts, position bits and triangles equal.
inline bool same_mesh(const mesh::Mesh& a, const mesh::Mesh& b) {
  const std::size_t n = a.vertex_count();
  if (n != b.vertex_count() || a.triangle_count() != b.triangle_count()) return false;
  for (const bool ok : {std::memcmp(a.x().data(), b.x().data(), n * sizeof(float)) == 0,
                        std::memcmp(a.y().data(), b.y().data(), n * sizeof(float)) == 0,
                        std::memcmp(a.z().data(), b.z().data(), n * sizeof(float)) == 0}) {
    if (!ok) return false;
  }
  const auto ta = a.triangle_indices();
  const auto tb = b.triangle_indices();
  return std::equal(ta.begin(), ta.end(), tb.begin(), tb.end()) && a.checksum() == b.checksum();
}

inline bool same_bits(glm::vec3 a, glm::vec3 b) {
  return std::bit_cast<std::uint32_t>(a.x) == std::bit_cast<std::uint32_t>(b.x) &&
         std::bit_cast<std::uint32_t>(a.y) == std::bit_cast<std::uint32_t>(b.y) &&
         std::bit_cast<std::uint32_t>(a.z) == std::bit_cast<std::uint32_t>(b.z);
}

inline bool same_frame(const math::Frame& a, const math::Frame& b) {
  return a.origin == b.origin && a.u == b.u && a.v == b.v && a.w == b.w;
}

inline bool same_entry(const session::UndoEntry& a, const session::UndoEntry& b) {
  return a.first_change == b.first_change && a.change_count == b.change_count &&
         a.first_triangle_change == b.first_triangle_change &&
         a.triangle_change_count == b.triangle_change_count && a.topology == b.topology &&
         a.vertices_before == b.vertices_before && a.vertices_after == b.vertices_after &&
         a.triangles_before == b.triangles_before && a.triangles_after == b.triangles_after &&
         a.object_move == b.object_move && same_frame(a.object_before, b.object_before) &&
         same_frame(a.object_after, b.object_after);
}

// Every entry, vertex change and triangle change equal, and the depths.
inline bool same_history(const session::UndoHistory& a, const session::UndoHistory& b) {
  if (a.undo_depth() != b.undo_depth() || a.redo_depth() != b.redo_depth() ||
      a.dropped_entries() != b.dropped_entries() || a.entries().size() != b.entries().size() ||
      a.changes().size() != b.changes().size() ||
      a.triangle_changes().size() != b.triangle_changes().size()) {
    return false;
  }
  for (std::size_t i = 0; i < a.entries().size(); ++i) {
    if (!same_entry(a.entries()[i], b.entries()[i])) return false;
  }
  for (std::size_t i = 0; i < a.changes().size(); ++i) {
    const session::VertexChange& x = a.changes()[i];
    const session::VertexChange& y = b.changes()[i];
    if (x.index != y.index || !same_bits(x.before, y.before) || !same_bits(x.after, y.after)) {
      return false;
    }
  }
  for (std::size_t i = 0; i < a.triangle_changes().size(); ++i) {
    const session::TriangleChange& x = a.triangle_changes()[i];
    const session::TriangleChange& y = b.triangle_changes()[i];
    if (x.index != y.index || x.before != y.before || x.after != y.after) return false;
  }
  return true;
}

inline std::size_t topology_count(const session::UndoHistory& h) {
  std::size_t n = 0;
  for (const session::UndoEntry& e : h.entries()) n += e.topology ? 1 : 0;
  return n;
}

// Mesh, history, pose and next sequence.
inline bool same_session(RefineStation& a, RefineStation& b) {
  return same_mesh(a.mesh(), b.mesh()) &&
         same_history(a.session->history(), b.session->history()) &&
         same_frame(a.session->object_pose(), b.session->object_pose()) &&
         a.session->next_sequence() == b.session->next_sequence();
}

// Where the sections of a version-2 file start.
struct CheckpointLayout {
  std::size_t positions = 0;
  std::size_t triangles = 0;
  std::size_t entries = 0;
  std::size_t changes = 0;
  std::size_t triangle_changes = 0;
  std::size_t crc = 0;
};

inline CheckpointLayout layout_of(const CheckpointHeader& h) {
  CheckpointLayout l;
  l.positions = kCheckpointHeaderBytes;
  l.triangles = l.positions + std::size_t{12} * h.vertex_count;
  l.entries = l.triangles + kCheckpointTriangleBytes * h.triangle_count;
  l.changes = l.entries + kCheckpointEntryBytes * h.entry_count;
  l.triangle_changes = l.changes + kCheckpointChangeBytes * h.used_changes;
  l.crc = l.triangle_changes + kCheckpointTriangleChangeBytes * h.used_triangle_changes;
  return l;
}

// Byte offsets of fields: header and entry.
inline constexpr std::size_t kHeaderVersion = 4, kHeaderVertexCount = 40;
inline constexpr std::size_t kEntryFirstTriangleChange = 16, kEntryTriangleChangeCount = 24,
                             kEntryVerticesBefore = 32, kEntryVerticesAfter = 36,
                             kEntryTrianglesBefore = 40, kEntryTrianglesAfter = 44,
                             kEntryTopology = 49;

inline std::uint64_t get_le(const Bytes& b, std::size_t at, std::size_t n) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < n; ++i)
    v |= std::uint64_t{std::to_integer<std::uint8_t>(b[at + i])} << (8 * i);
  return v;
}

inline void put_le(Bytes& b, std::size_t at, std::size_t n, std::uint64_t v) {
  for (std::size_t i = 0; i < n; ++i) b[at + i] = static_cast<std::byte>((v >> (8 * i)) & 0xffu);
}

// The CRC made right again after an edit.
inline void reseal(Bytes& b) {
  put_le(b, b.size() - 4, 4, crc32(std::span<const std::byte>(b).first(b.size() - 4)));
}

inline CheckpointHeader header_of(const Bytes& b) {
  auto file = std::make_unique<CheckpointFile>();
  file->load(b);
  const auto h = read_checkpoint_header(*file);
  EXPECT_TRUE(h.ok());
  return h.ok() ? *h : CheckpointHeader{};
}

}  // namespace twister::checkpoint::test_support
