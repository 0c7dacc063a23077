#include "twister/input/undo_history.hpp"

#include <algorithm>

#include "twister/base/assert.hpp"

namespace twister::input {

UndoHistory::UndoHistory(std::span<VertexChange> changes, std::span<UndoEntry> entries)
    : changes_(changes), entries_(entries) {
  TWISTER_ASSERT(!entries.empty());
}

void UndoHistory::clear() {
  entry_count_ = 0;
  undo_count_ = 0;
  open_ = false;
  overflow_ = false;
}

std::size_t UndoHistory::used_changes() const {
  if (entry_count_ == 0) return 0;
  const UndoEntry& last = entries_[entry_count_ - 1];
  return last.first_change + last.change_count;
}

// Entries and their changes are kept packed at the front of the spans; dropping
// the oldest shifts the rest down. That copy is rare (only when memory is full)
// and keeps every entry contiguous, so undo/redo are plain loops.
void UndoHistory::drop_oldest() {
  TWISTER_ASSERT(entry_count_ > 0);
  const std::size_t shift = entries_[0].change_count;
  // The open entry's changes sit after the closed ones and move with them.
  const std::size_t used =
      open_ ? open_entry_.first_change + open_entry_.change_count : used_changes();
  std::copy(changes_.begin() + static_cast<std::ptrdiff_t>(shift),
            changes_.begin() + static_cast<std::ptrdiff_t>(used), changes_.begin());
  std::copy(entries_.begin() + 1, entries_.begin() + static_cast<std::ptrdiff_t>(entry_count_),
            entries_.begin());
  --entry_count_;
  if (undo_count_ > 0) --undo_count_;
  for (std::size_t i = 0; i < entry_count_; ++i) entries_[i].first_change -= shift;
  if (open_) open_entry_.first_change -= shift;
  ++dropped_;
}

void UndoHistory::begin_entry() {
  entry_count_ = undo_count_;  // another commit ends the redo branch
  if (entry_count_ == entries_.size()) drop_oldest();
  open_ = true;
  overflow_ = false;
  open_entry_ = UndoEntry{};
  open_entry_.first_change = used_changes();
}

Status UndoHistory::record(std::uint32_t index, glm::vec3 before, glm::vec3 after) {
  if (!open_) return StatusCode::failed_precondition;
  if (overflow_) return StatusCode::resource_exhausted;
  while (open_entry_.first_change + open_entry_.change_count == changes_.size()) {
    if (entry_count_ == 0) {
      overflow_ = true;
      return StatusCode::resource_exhausted;
    }
    drop_oldest();
  }
  changes_[open_entry_.first_change + open_entry_.change_count++] = {index, before, after};
  return ok_status();
}

void UndoHistory::record_object(const math::Frame& before, const math::Frame& after) {
  if (!open_) return;
  open_entry_.object_move = true;
  open_entry_.object_before = before;
  open_entry_.object_after = after;
}

Status UndoHistory::end_entry() {
  if (!open_) return StatusCode::failed_precondition;
  open_ = false;
  if (overflow_) {
    clear();  // older entries were dropped to make room; nothing consistent is left
    ++dropped_;
    return StatusCode::resource_exhausted;
  }
  entries_[entry_count_++] = open_entry_;
  undo_count_ = entry_count_;
  return ok_status();
}

Result<UndoStep> UndoHistory::undo(mesh::Mesh& mesh) {
  if (open_ || undo_count_ == 0) return StatusCode::failed_precondition;
  const UndoEntry& e = entries_[undo_count_ - 1];
  for (std::size_t i = 0; i < e.change_count; ++i) {
    if (changes_[e.first_change + i].index >= mesh.vertex_count()) return StatusCode::out_of_range;
  }
  // Newest change first, so a vertex recorded twice ends at its oldest position.
  for (std::size_t i = e.change_count; i-- > 0;) {
    const VertexChange& c = changes_[e.first_change + i];
    mesh.set_position(c.index, c.before);
  }
  --undo_count_;
  return UndoStep{e.object_move, e.object_before, e.change_count};
}

Result<UndoStep> UndoHistory::redo(mesh::Mesh& mesh) {
  if (open_ || undo_count_ == entry_count_) return StatusCode::failed_precondition;
  const UndoEntry& e = entries_[undo_count_];
  for (std::size_t i = 0; i < e.change_count; ++i) {
    if (changes_[e.first_change + i].index >= mesh.vertex_count()) return StatusCode::out_of_range;
  }
  for (std::size_t i = 0; i < e.change_count; ++i) {
    const VertexChange& c = changes_[e.first_change + i];
    mesh.set_position(c.index, c.after);
  }
  ++undo_count_;
  return UndoStep{e.object_move, e.object_after, e.change_count};
}

Status UndoHistory::adopt(std::size_t entry_count, std::size_t undo_count, std::size_t dropped) {
  bool ok = !open_ && entry_count <= entries_.size() && undo_count <= entry_count;
  std::size_t next = 0;
  for (std::size_t i = 0; ok && i < entry_count; ++i) {
    const UndoEntry& e = entries_[i];
    ok = e.first_change == next && e.change_count <= changes_.size() - next;
    next += ok ? e.change_count : 0;
  }
  if (!ok) {
    clear();
    return StatusCode::invalid_argument;
  }
  entry_count_ = entry_count;
  undo_count_ = undo_count;
  dropped_ = dropped;
  overflow_ = false;
  return ok_status();
}

}  // namespace twister::input
