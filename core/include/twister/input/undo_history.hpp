// UndoHistory: undo and redo of committed strokes in bounded, caller-owned memory.
// Each entry stores, per changed vertex, its exact position before and after the
// commit (and, for an object move, the object pose before and after), so undo then
// redo restores the mesh bit-identically. When the memory is full the oldest
// entries are dropped; an entry larger than all of the memory is not kept (and the
// history is emptied): record() reports it. A new commit drops the redo tail.
// No allocation; not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>

#include "twister/base/result.hpp"
#include "twister/math/frame.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::input {

struct VertexChange {
  std::uint32_t index = 0;
  glm::vec3 before{0.0f};
  glm::vec3 after{0.0f};
};

struct UndoEntry {
  std::size_t first_change = 0;
  std::size_t change_count = 0;
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
  UndoHistory(std::span<VertexChange> changes, std::span<UndoEntry> entries);

  // Starts recording a commit (drops the redo tail; drops the oldest entry when
  // every entry slot is taken).
  void begin_entry();
  // Records a vertex change of the open entry (call before or after changing the
  // mesh, with both positions). Drops the oldest entries when the change memory is
  // full. resource_exhausted: the entry alone exceeds the memory; it will be
  // discarded at end_entry() (the commit itself still happens, it is just not
  // undoable). failed_precondition: no open entry.
  Status record(std::uint32_t index, glm::vec3 before, glm::vec3 after);
  // Records the object pose change of the open entry.
  void record_object(const math::Frame& before, const math::Frame& after);
  // Closes the open entry. resource_exhausted: it overflowed and was discarded.
  Status end_entry();

  bool can_undo() const { return undo_count_ > 0; }
  bool can_redo() const { return undo_count_ < entry_count_; }
  std::size_t undo_depth() const { return undo_count_; }
  std::size_t redo_depth() const { return entry_count_ - undo_count_; }
  std::size_t dropped_entries() const { return dropped_; }

  // Restores the positions before the newest undoable entry.
  // failed_precondition: nothing to undo (or an entry is open).
  // out_of_range: an index is beyond the mesh (mesh replaced under the history).
  Result<UndoStep> undo(mesh::Mesh& mesh);
  // Re-applies the oldest undone entry. failed_precondition: nothing to redo.
  Result<UndoStep> redo(mesh::Mesh& mesh);

  void clear();

  // Checkpoint support (SessionCheckpoint). The kept entries, oldest first, and their
  // vertex changes (entries()[i] covers changes()[first_change, + change_count)).
  std::span<const UndoEntry> entries() const { return entries_.first(entry_count_); }
  std::span<const VertexChange> changes() const { return changes_.first(used_changes()); }
  std::size_t entry_capacity() const { return entries_.size(); }
  std::size_t change_capacity() const { return changes_.size(); }
  // Restore: the caller writes the entries and changes straight into these spans,
  // then adopt() makes them the history. adopt() checks that the entries are packed
  // and contiguous from change 0 and fit; invalid_argument (the history is then
  // cleared) otherwise. No entry may be open.
  std::span<UndoEntry> entry_storage() { return entries_; }
  std::span<VertexChange> change_storage() { return changes_; }
  Status adopt(std::size_t entry_count, std::size_t undo_count, std::size_t dropped);

 private:
  void drop_oldest();
  std::size_t used_changes() const;

  std::span<VertexChange> changes_;
  std::span<UndoEntry> entries_;
  std::size_t entry_count_ = 0;  // closed entries kept (undoable + redoable)
  std::size_t undo_count_ = 0;   // entries [0, undo_count_) can be undone
  bool open_ = false;
  bool overflow_ = false;
  UndoEntry open_entry_{};
  std::size_t dropped_ = 0;
};

template <std::size_t kChanges, std::size_t kEntries>
class UndoHistoryWithStorage : public UndoHistory {
 public:
  UndoHistoryWithStorage() : UndoHistory(changes_storage_, entries_storage_) {}
  UndoHistoryWithStorage(const UndoHistoryWithStorage&) = delete;
  UndoHistoryWithStorage& operator=(const UndoHistoryWithStorage&) = delete;

 private:
  std::array<VertexChange, kChanges> changes_storage_{};
  std::array<UndoEntry, kEntries> entries_storage_{};
};

}  // namespace twister::input
