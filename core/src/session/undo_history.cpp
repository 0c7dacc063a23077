#include "twister/session/undo_history.hpp"

#include <algorithm>

#include "twister/base/assert.hpp"

namespace twister::session {

UndoHistory::UndoHistory(std::span<VertexChange> changes, std::span<UndoEntry> entries,
                         std::span<TriangleChange> triangle_changes)
    : changes_(changes), entries_(entries), triangle_changes_(triangle_changes) {
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

std::size_t UndoHistory::used_triangle_changes() const {
  if (entry_count_ == 0) return 0;
  const UndoEntry& last = entries_[entry_count_ - 1];
  return last.first_triangle_change + last.triangle_change_count;
}

// Entries and their changes are kept packed at the front of the spans; dropping
// the oldest shifts the rest down. That copy is rare (only when memory is full)
// and keeps every entry contiguous, so undo/redo are plain loops.
void UndoHistory::drop_oldest() {
  TWISTER_ASSERT(entry_count_ > 0);
  const std::size_t shift = entries_[0].change_count;
  const std::size_t triangle_shift = entries_[0].triangle_change_count;
  // The open entry's changes sit after the closed ones and move with them.
  const std::size_t used =
      open_ ? open_entry_.first_change + open_entry_.change_count : used_changes();
  const std::size_t triangles_used =
      open_ ? open_entry_.first_triangle_change + open_entry_.triangle_change_count
            : used_triangle_changes();
  std::copy(changes_.begin() + static_cast<std::ptrdiff_t>(shift),
            changes_.begin() + static_cast<std::ptrdiff_t>(used), changes_.begin());
  std::copy(triangle_changes_.begin() + static_cast<std::ptrdiff_t>(triangle_shift),
            triangle_changes_.begin() + static_cast<std::ptrdiff_t>(triangles_used),
            triangle_changes_.begin());
  std::copy(entries_.begin() + 1, entries_.begin() + static_cast<std::ptrdiff_t>(entry_count_),
            entries_.begin());
  --entry_count_;
  if (undo_count_ > 0) --undo_count_;
  for (std::size_t i = 0; i < entry_count_; ++i) {
    entries_[i].first_change -= shift;
    entries_[i].first_triangle_change -= triangle_shift;
  }
  if (open_) {
    open_entry_.first_change -= shift;
    open_entry_.first_triangle_change -= triangle_shift;
  }
  ++dropped_;
}

void UndoHistory::begin_entry() {
  entry_count_ = undo_count_;  // another commit ends the redo branch
  if (entry_count_ == entries_.size()) drop_oldest();
  open_ = true;
  overflow_ = false;
  open_entry_ = UndoEntry{};
  open_entry_.first_change = used_changes();
  open_entry_.first_triangle_change = used_triangle_changes();
}

template <typename End>
bool UndoHistory::make_room(End end, std::size_t pool_size) {
  while (end() == pool_size) {
    if (entry_count_ == 0) {
      overflow_ = true;
      return false;
    }
    drop_oldest();
  }
  return true;
}

Status UndoHistory::record(std::uint32_t index, glm::vec3 before, glm::vec3 after) {
  if (!open_) return StatusCode::failed_precondition;
  const auto end = [this] { return open_entry_.first_change + open_entry_.change_count; };
  if (overflow_ || !make_room(end, changes_.size())) return StatusCode::resource_exhausted;
  changes_[end()] = {index, before, after};
  ++open_entry_.change_count;
  return ok_status();
}

Status UndoHistory::record_triangle(std::uint32_t index,
                                    const std::array<std::uint32_t, 3>& before) {
  if (!open_) return StatusCode::failed_precondition;
  const auto end = [this] {
    return open_entry_.first_triangle_change + open_entry_.triangle_change_count;
  };
  if (overflow_ || !make_room(end, triangle_changes_.size())) {
    return StatusCode::resource_exhausted;
  }
  triangle_changes_[end()] = {index, before, before};
  ++open_entry_.triangle_change_count;
  return ok_status();
}

Status UndoHistory::record_topology(const mesh::Mesh& mesh, std::uint32_t vertices_before,
                                    std::uint32_t triangles_before) {
  if (!open_) return StatusCode::failed_precondition;
  open_entry_.topology = true;
  open_entry_.vertices_before = vertices_before;
  open_entry_.triangles_before = triangles_before;
  open_entry_.vertices_after = static_cast<std::uint32_t>(mesh.vertex_count());
  open_entry_.triangles_after = static_cast<std::uint32_t>(mesh.triangle_count());
  if (overflow_) return StatusCode::resource_exhausted;
  for (std::size_t i = 0; i < open_entry_.triangle_change_count; ++i) {
    TriangleChange& c = triangle_changes_[open_entry_.first_triangle_change + i];
    c.after = mesh.triangle(c.index);
  }
  for (std::uint32_t t = triangles_before; t < mesh.triangle_count(); ++t) {
    const auto v = mesh.triangle(t);
    TWISTER_TRY(record_triangle(t, v));
  }
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

// The mesh is the one the entry applies to: as after it (undo) or before it (redo).
bool UndoHistory::fits(const UndoEntry& e, const mesh::Mesh& mesh, bool after) const {
  const std::size_t vertices =
      e.topology ? (after ? e.vertices_after : e.vertices_before) : mesh.vertex_count();
  if (e.topology && (mesh.vertex_count() != vertices ||
                     mesh.triangle_count() != (after ? e.triangles_after : e.triangles_before))) {
    return false;
  }
  const std::size_t needed = e.topology ? e.vertices_after : vertices;
  for (std::size_t i = 0; i < e.change_count; ++i) {
    if (changes_[e.first_change + i].index >= needed) return false;
  }
  return true;
}

void UndoHistory::restore_triangles(const UndoEntry& e, mesh::Mesh& mesh, bool after) const {
  for (std::size_t i = 0; i < e.triangle_change_count; ++i) {
    const TriangleChange& c = triangle_changes_[e.first_triangle_change + i];
    if (after) {
      mesh.set_triangle(c.index, c.after);
    } else if (c.index < e.triangles_before) {
      mesh.set_triangle(c.index, c.before);
    }
  }
}

// Puts back the triangles of refined entry `e` (the mesh as after it) when that leaves
// every triangle before triangles_before on vertices before vertices_before: its own
// triangles must hold their indices after it and every other triangle must already
// refer to the older vertices. Always so for a history recorded here; a restored one
// (a checkpoint's) is only known to be so by this check. false: nothing changed.
bool UndoHistory::undo_triangles(const UndoEntry& e, mesh::Mesh& mesh) const {
  const auto below = [](const std::array<std::uint32_t, 3>& t, std::uint32_t n) {
    return t[0] < n && t[1] < n && t[2] < n;
  };
  for (std::size_t i = 0; i < e.triangle_change_count; ++i) {
    const TriangleChange& c = triangle_changes_[e.first_triangle_change + i];
    if (c.index >= mesh.triangle_count() || mesh.triangle(c.index) != c.after ||
        (c.index < e.triangles_before && !below(c.before, e.vertices_before))) {
      return false;
    }
  }
  restore_triangles(e, mesh, false);
  const std::span<const std::uint32_t> kept =
      mesh.triangle_indices().first(std::size_t{3} * e.triangles_before);
  if (std::all_of(kept.begin(), kept.end(),
                  [&](std::uint32_t v) { return v < e.vertices_before; })) {
    return true;
  }
  restore_triangles(e, mesh, true);  // exactly as it was: each held its `after`
  return false;
}

Result<UndoStep> UndoHistory::undo(mesh::Mesh& mesh) {
  if (open_ || undo_count_ == 0) return StatusCode::failed_precondition;
  const UndoEntry& e = entries_[undo_count_ - 1];
  if (!fits(e, mesh, true)) return StatusCode::out_of_range;
  if (e.topology && !undo_triangles(e, mesh)) return StatusCode::out_of_range;
  // Newest change first, so a vertex recorded twice ends at its oldest position.
  for (std::size_t i = e.change_count; i-- > 0;) {
    const VertexChange& c = changes_[e.first_change + i];
    if (!e.topology || c.index < e.vertices_before) mesh.set_position(c.index, c.before);
  }
  if (e.topology) {
    mesh.resize(e.vertices_before, e.triangles_before).ignore();  // shrinking always fits
  }
  --undo_count_;
  return UndoStep{e.object_move, e.object_before, e.change_count};
}

Result<UndoStep> UndoHistory::redo(mesh::Mesh& mesh) {
  if (open_ || undo_count_ == entry_count_) return StatusCode::failed_precondition;
  const UndoEntry& e = entries_[undo_count_];
  if (!fits(e, mesh, false)) return StatusCode::out_of_range;
  if (e.topology) {
    if (!mesh.resize(e.vertices_after, e.triangles_after).ok()) return StatusCode::out_of_range;
    restore_triangles(e, mesh, true);
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
  std::size_t next_triangle = 0;
  for (std::size_t i = 0; ok && i < entry_count; ++i) {
    const UndoEntry& e = entries_[i];
    ok = e.first_change == next && e.change_count <= changes_.size() - next &&
         e.first_triangle_change == next_triangle &&
         e.triangle_change_count <= triangle_changes_.size() - next_triangle;
    next += ok ? e.change_count : 0;
    next_triangle += ok ? e.triangle_change_count : 0;
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

}  // namespace twister::session
