// UndoHistory: undo and redo of committed strokes in bounded, caller-owned memory.
// Each entry stores, per changed vertex, its exact position before and after the
// commit (and, for an object move, the object pose before and after), so undo then
// redo restores the mesh bit-identically. A commit that refined the mesh also
// changed its topology: the entry then holds the vertex and triangle counts before
// and after, every pre-existing triangle it rewrote (indices before and after) and
// every triangle it appended (indices after); the appended vertices are vertex
// changes beyond the old count. Undo puts the triangles back and drops what was
// appended; redo appends and rewrites again, so both are bit-identical (checksum)
// including topology. Two fixed pools: vertex changes and triangle changes. When
// either is full the oldest entries are dropped; an entry larger than a whole pool
// is not kept (and the history is emptied): record() / record_triangle() report it.
// A new commit drops the redo tail. No allocation; not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>

#include "twister/base/result.hpp"
#include "twister/math/frame.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::session {

struct VertexChange {
  std::uint32_t index = 0;
  glm::vec3 before{0.0f};
  glm::vec3 after{0.0f};
};

// A triangle a commit rewrote (`before` and `after`) or appended (`after` only).
struct TriangleChange {
  std::uint32_t index = 0;
  std::array<std::uint32_t, 3> before{};
  std::array<std::uint32_t, 3> after{};
};

struct UndoEntry {
  std::size_t first_change = 0;
  std::size_t change_count = 0;
  std::size_t first_triangle_change = 0;
  std::size_t triangle_change_count = 0;
  bool topology = false;  // counts and triangles changed (refinement)
  std::uint32_t vertices_before = 0;
  std::uint32_t vertices_after = 0;
  std::uint32_t triangles_before = 0;
  std::uint32_t triangles_after = 0;
  bool object_move = false;
  math::Frame object_before{};
  math::Frame object_after{};
};

// What undo()/redo() did, for the caller to apply the object pose.
struct UndoStep {
  bool object_move = false;
  math::Frame object_pose{};  // the pose to set when object_move
  std::size_t vertex_count = 0;
};

class UndoHistory {
 public:
  // `triangle_changes` may be empty: then an entry that changes the topology is
  // never undoable.
  UndoHistory(std::span<VertexChange> changes, std::span<UndoEntry> entries,
              std::span<TriangleChange> triangle_changes = {});

  // Starts recording a commit (drops the redo tail; drops the oldest entry when
  // every entry slot is taken).
  void begin_entry();
  // Records a vertex change of the open entry (call before or after changing the
  // mesh, with both positions). Drops the oldest entries when the change memory is
  // full. resource_exhausted: the entry alone exceeds the memory; it will be
  // discarded at end_entry() (the commit itself still happens, it is just not
  // undoable). failed_precondition: no open entry.
  Status record(std::uint32_t index, glm::vec3 before, glm::vec3 after);
  // Records a pre-existing triangle of the open entry before it is rewritten (its
  // indices after are taken by record_topology()). Errors as record().
  Status record_triangle(std::uint32_t index, const std::array<std::uint32_t, 3>& before);
  // After a topology change of the open entry: the mesh had `vertices_before` /
  // `triangles_before` (vertices appended since are recorded with record(), their
  // `before` unused). Takes the recorded triangles' indices after and every appended
  // triangle from `mesh`. Errors as record().
  Status record_topology(const mesh::Mesh& mesh, std::uint32_t vertices_before,
                         std::uint32_t triangles_before);
  // Records the object pose change of the open entry.
  void record_object(const math::Frame& before, const math::Frame& after);
  // Closes the open entry. resource_exhausted: it overflowed and was discarded.
  Status end_entry();

  bool can_undo() const { return undo_count_ > 0; }
  bool can_redo() const { return undo_count_ < entry_count_; }
  std::size_t undo_depth() const { return undo_count_; }
  std::size_t redo_depth() const { return entry_count_ - undo_count_; }
  std::size_t dropped_entries() const { return dropped_; }

  // Restores the positions (and topology) before the newest undoable entry.
  // failed_precondition: nothing to undo (or an entry is open).
  // out_of_range: an index or count does not match the mesh (mesh replaced under the
  // history), or a refined entry's triangles do not (its own triangles not as it left
  // them, or another triangle on a vertex it added: a history restored from a
  // checkpoint that does not fit its mesh); nothing changed. A refined entry's undo
  // looks at every triangle before its triangles_before once.
  Result<UndoStep> undo(mesh::Mesh& mesh);
  // Re-applies the oldest undone entry. failed_precondition: nothing to redo.
  Result<UndoStep> redo(mesh::Mesh& mesh);

  void clear();

  // Checkpoint support (SessionCheckpoint). The kept entries, oldest first, and their
  // vertex and triangle changes (entries()[i] covers changes()[first_change, +
  // change_count) and triangle_changes()[first_triangle_change, + triangle_change_count)).
  std::span<const UndoEntry> entries() const { return entries_.first(entry_count_); }
  std::span<const VertexChange> changes() const { return changes_.first(used_changes()); }
  std::span<const TriangleChange> triangle_changes() const {
    return triangle_changes_.first(used_triangle_changes());
  }
  std::size_t entry_capacity() const { return entries_.size(); }
  std::size_t change_capacity() const { return changes_.size(); }
  std::size_t triangle_change_capacity() const { return triangle_changes_.size(); }
  // Restore: the caller writes the entries and both kinds of changes straight into
  // these spans, then adopt() makes them the history. adopt() checks that the entries
  // are packed and contiguous from change 0 and triangle change 0 and fit both pools;
  // invalid_argument (the history is then cleared) otherwise. No entry may be open.
  // (Whether the entries fit the mesh is the caller's check: undo() and redo() still
  // refuse an entry whose counts or vertex indices do not.)
  std::span<UndoEntry> entry_storage() { return entries_; }
  std::span<VertexChange> change_storage() { return changes_; }
  std::span<TriangleChange> triangle_change_storage() { return triangle_changes_; }
  Status adopt(std::size_t entry_count, std::size_t undo_count, std::size_t dropped);

 private:
  void drop_oldest();
  std::size_t used_changes() const;
  std::size_t used_triangle_changes() const;
  // Makes room for one more change of the open entry in a pool whose open end is
  // `end()` (dropping the oldest entries); false: the entry overflowed.
  template <typename End>
  bool make_room(End end, std::size_t pool_size);
  bool fits(const UndoEntry& e, const mesh::Mesh& mesh, bool after) const;
  void restore_triangles(const UndoEntry& e, mesh::Mesh& mesh, bool after) const;
  bool undo_triangles(const UndoEntry& e, mesh::Mesh& mesh) const;

  std::span<VertexChange> changes_;
  std::span<UndoEntry> entries_;
  std::span<TriangleChange> triangle_changes_;
  std::size_t entry_count_ = 0;  // closed entries kept (undoable + redoable)
  std::size_t undo_count_ = 0;   // entries [0, undo_count_) can be undone
  bool open_ = false;
  bool overflow_ = false;
  UndoEntry open_entry_{};
  std::size_t dropped_ = 0;
};

// kChanges vertex changes and as many triangle changes, kEntries entries.
template <std::size_t kChanges, std::size_t kEntries>
class UndoHistoryWithStorage : public UndoHistory {
 public:
  UndoHistoryWithStorage() : UndoHistory(changes_storage_, entries_storage_, triangle_storage_) {}
  UndoHistoryWithStorage(const UndoHistoryWithStorage&) = delete;
  UndoHistoryWithStorage& operator=(const UndoHistoryWithStorage&) = delete;

 private:
  std::array<VertexChange, kChanges> changes_storage_{};
  std::array<UndoEntry, kEntries> entries_storage_{};
  std::array<TriangleChange, kChanges> triangle_storage_{};
};

}  // namespace twister::session
