// The undo history of a checkpoint: entries, vertex changes, triangle changes, each
// value checked before it is used. The entries are read once in order (packed and
// contiguous in both pools, the refined ones chained by their counts, the mesh at
// the counts the undoable ones end at); the changes are then checked against the
// counts before and after their own entry, which a second cursor re-reads from the
// file (verify keeps nothing, so no per-entry memory is needed).
#include <array>
#include <span>

#include "checkpoint_format.hpp"
#include "checkpoint_input.hpp"

namespace twister::checkpoint::format {
namespace {

struct Counts {
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  bool operator==(const Counts&) const = default;
};

Counts before_of(const session::UndoEntry& e) { return {e.vertices_before, e.triangles_before}; }
Counts after_of(const session::UndoEntry& e) { return {e.vertices_after, e.triangles_after}; }

// The mesh's counts along the entries, oldest first: a refined entry must start
// where the chain stands and moves it; any other entry keeps it.
class CountChain {
 public:
  void start(Counts counts) {
    first_ = counts;
    now_ = counts;
    known_ = true;
  }
  bool known() const { return known_; }
  Counts first() const { return first_; }  // the counts it started at
  Counts now() const { return now_; }
  // false: a refined entry that does not start at the chain's counts.
  bool step(const session::UndoEntry& e) {
    if (!e.topology) return true;
    if (!known_) start(before_of(e));  // the entries before it have the same counts
    if (before_of(e) != now_) return false;
    now_ = after_of(e);
    return true;
  }

 private:
  Counts first_{};
  Counts now_{};
  bool known_ = false;
};

bool topology_fits(const session::UndoEntry& e, const CheckpointHeader& h) {
  return !e.topology ||
         (e.vertices_before <= e.vertices_after && e.vertices_after <= h.vertex_capacity &&
          e.triangles_before <= e.triangles_after && e.triangles_after <= h.triangle_capacity);
}

// The entries in order; `start`: the counts before the first one.
Status read_entries(Input& in, const CheckpointHeader& h, session::SculptSession* target,
                    Counts& start) {
  const Counts mesh{h.vertex_count, h.triangle_count};
  CountChain chain;
  // Where the undoable entries end the mesh stands (or, before any refined entry, the
  // counts every entry has).
  const auto settle = [&] {
    if (!chain.known()) chain.start(mesh);
    return chain.now() == mesh;
  };
  std::span<const std::byte> bytes;
  std::uint64_t next_change = 0;
  std::uint64_t next_triangle = 0;
  for (std::uint64_t i = 0; i < h.entry_count; ++i) {
    if (i == h.undo_count && !settle()) return StatusCode::data_loss;
    session::UndoEntry e;
    if (!in.take(kCheckpointEntryBytes, bytes) || !decode_entry(bytes, e) ||
        e.first_change != next_change || e.change_count > h.used_changes - next_change ||
        e.first_triangle_change != next_triangle ||
        e.triangle_change_count > h.used_triangle_changes - next_triangle || !topology_fits(e, h) ||
        !chain.step(e)) {
      return StatusCode::data_loss;
    }
    next_change += e.change_count;
    next_triangle += e.triangle_change_count;
    if (target != nullptr) target->restore_target().history.entry_storage()[i] = e;
  }
  if (h.undo_count == h.entry_count && !settle()) return StatusCode::data_loss;
  if (next_change != h.used_changes || next_triangle != h.used_triangle_changes) {
    return StatusCode::data_loss;
  }
  start = chain.first();
  return ok_status();
}

// The entries again, from the file, with the counts before and after each.
class EntryReplay {
 public:
  EntryReplay(ports::Storage& storage, const CheckpointHeader& h, Counts start)
      : in_(storage, window_, entries_offset(h)) {
    chain_.start(start);
  }
  // false: unreadable, or not the entry read before (the file changed meanwhile).
  bool next(session::UndoEntry& e, Counts& before, Counts& after) {
    std::span<const std::byte> bytes;
    if (!in_.take(kCheckpointEntryBytes, bytes) || !decode_entry(bytes, e)) return false;
    before = chain_.now();
    if (!chain_.step(e)) return false;
    after = chain_.now();
    return true;
  }

 private:
  std::array<std::byte, 2 * kMaxElementBytes> window_{};
  Input in_;
  CountChain chain_;
};

Status read_changes(Input& in, ports::Storage& storage, const CheckpointHeader& h,
                    session::SculptSession* target, Counts start) {
  EntryReplay entries(storage, h, start);
  std::span<const std::byte> bytes;
  std::uint64_t at = 0;
  for (std::uint64_t i = 0; i < h.entry_count; ++i) {
    session::UndoEntry e;
    Counts before;
    Counts after;
    if (!entries.next(e, before, after)) return StatusCode::data_loss;
    for (std::size_t k = 0; k < e.change_count; ++k, ++at) {
      session::VertexChange c;
      if (at >= h.used_changes || !in.take(kCheckpointChangeBytes, bytes) ||
          !decode_change(bytes, c) || c.index >= after.vertices) {
        return StatusCode::data_loss;
      }
      if (target != nullptr) target->restore_target().history.change_storage()[at] = c;
    }
  }
  return at == h.used_changes ? ok_status() : Status(StatusCode::data_loss);
}

bool below(const std::array<std::uint32_t, 3>& t, std::uint64_t vertices) {
  return t[0] < vertices && t[1] < vertices && t[2] < vertices;
}

// A refined entry's triangle changes: the triangles it rewrote (index below its
// triangles_before, indices before and after within its counts), then every triangle
// it appended, in order.
class TriangleRun {
 public:
  TriangleRun(Counts before, Counts after) : before_(before), after_(after) {}
  bool take(const session::TriangleChange& c) {
    if (!below(c.after, after_.vertices)) return false;
    if (appended_ == 0 && c.index < before_.triangles) return below(c.before, before_.vertices);
    if (c.index != before_.triangles + appended_) return false;
    ++appended_;
    return below(c.before, after_.vertices);
  }
  bool complete() const { return before_.triangles + appended_ == after_.triangles; }

 private:
  Counts before_;
  Counts after_;
  std::uint64_t appended_ = 0;
};

Status read_triangle_changes(Input& in, ports::Storage& storage, const CheckpointHeader& h,
                             session::SculptSession* target, Counts start) {
  EntryReplay entries(storage, h, start);
  std::span<const std::byte> bytes;
  std::uint64_t at = 0;
  for (std::uint64_t i = 0; i < h.entry_count; ++i) {
    session::UndoEntry e;
    Counts before;
    Counts after;
    if (!entries.next(e, before, after)) return StatusCode::data_loss;
    TriangleRun run(before, after);
    for (std::size_t k = 0; k < e.triangle_change_count; ++k, ++at) {
      if (at >= h.used_triangle_changes || !in.take(kCheckpointTriangleChangeBytes, bytes)) {
        return StatusCode::data_loss;
      }
      const session::TriangleChange c = decode_triangle_change(bytes);
      if (!run.take(c)) return StatusCode::data_loss;
      if (target != nullptr) target->restore_target().history.triangle_change_storage()[at] = c;
    }
    if (e.topology && !run.complete()) return StatusCode::data_loss;
  }
  return at == h.used_triangle_changes ? ok_status() : Status(StatusCode::data_loss);
}

}  // namespace

std::uint64_t entries_offset(const CheckpointHeader& h) {
  return kCheckpointHeaderBytes + std::uint64_t{12} * h.vertex_count +
         std::uint64_t{kCheckpointTriangleBytes} * h.triangle_count;
}

Status walk_history(Input& in, ports::Storage& storage, const CheckpointHeader& h,
                    session::SculptSession* target) {
  Counts start;
  TWISTER_TRY(read_entries(in, h, target, start));
  TWISTER_TRY(read_changes(in, storage, h, target, start));
  return read_triangle_changes(in, storage, h, target, start);
}

}  // namespace twister::checkpoint::format
