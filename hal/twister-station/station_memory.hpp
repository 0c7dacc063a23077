// twister-station's memory, sized once at start-up from the model (docs/reliability.md
// "Memory budget"). Per vertex of capacity: 12 B positions (MeshBuffer) + 12 B live
// warped columns + 12 B warp plan (index + two weights); per triangle 12 B indices;
// the undo history is fixed: undo_changes x 28 B (one per vertex a commit moves) +
// undo_entries x 248 B (one per commit); 12 B per vertex of normals; with refinement on
// ([sculpt] refine) the refiner's 48 B per vertex + 32 B per triangle, the undo pool
// of refined triangles (262144 x 28 B) and 12 B per vertex of a clutch chain's start; with --link
// the display link adds 12 B per vertex + 12 B per triangle (its copy of the mesh) + its frame
// buffer (512 frames, as DisplayLink::open sizes it) and, per spectator slot ([link]
// max_spectators, default 4), a queue of kSpectatorQueueFrames frames, plus one such
// staging buffer for a commit's change set and the slots' fixed part (sizeof
// StationSpectators: 8 slots of an 8 KiB urgent queue, a decoder and a live stream);
// symmetric strokes ([sculpt] symmetry, and any
// journal that holds them) 36 B per vertex: 12 B of chain-start positions, the float path's
// 8 B of sort words and 16 B of kept weights (meshio::SymmetryBuffer::bytes_for).
// WorkMemory is the core's working memory as ONE arena of exactly
// budget.live + budget.plan + budget.undo + budget.normals bytes, carved into the spans
// SculptStorage needs; nothing else is allocated for the core after start-up.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "twister/meshio/refiner_buffer.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::station_app {

// Frames in each spectator's bulk queue and in the spectators' staging buffer
// (DisplayLink::open sizes them so).
inline constexpr std::size_t kSpectatorQueueFrames = 64;

struct MemoryBudget {
  std::size_t mesh = 0;      // positions and triangle indices (the model)
  std::size_t live = 0;      // the live stroke's warped columns
  std::size_t plan = 0;      // warp plan: influenced indices and two weight columns
  std::size_t undo = 0;      // undo history: vertex changes and entries
  std::size_t normals = 0;   // vertex normals (for the display)
  std::size_t refine = 0;    // refiner and refined triangles' undo pool (0 when off)
  std::size_t link = 0;      // display link: its mesh copy and frame buffer (0 without --link)
  std::size_t symmetry = 0;  // symmetric strokes: chain-start columns, the warp, the float
                             // path's sorted order and weights
  std::size_t total() const {
    return mesh + live + plan + undo + normals + refine + link + symmetry;
  }
};

MemoryBudget memory_budget(std::size_t vertex_capacity, std::size_t triangle_capacity,
                           std::size_t undo_changes = session::kDefaultUndoChanges,
                           std::size_t undo_entries = session::kDefaultUndoEntries,
                           bool link = false, bool refine = false, std::size_t max_spectators = 4);

// The spectators' part of the link: their queues, the staging buffer, the slots.
std::size_t spectator_link_bytes(std::size_t max_spectators);

// The SculptSession's working memory for a mesh of `vertex_capacity` vertices: one
// arena of memory_budget(...).live + plan + undo + normals bytes.
class WorkMemory {
 public:
  explicit WorkMemory(std::size_t vertex_capacity,
                      std::size_t undo_changes = session::kDefaultUndoChanges,
                      std::size_t undo_entries = session::kDefaultUndoEntries);
  session::SculptStorage storage();
  std::size_t arena_bytes() const { return bytes_; }

 private:
  std::size_t bytes_ = 0;
  std::unique_ptr<std::byte[]> arena_;
  session::SculptStorage storage_{};
};

// Refinement's working memory (only when [sculpt] refine is on): the refiner for the
// mesh's capacities, the undo pool of refined commits' triangles and a clutch chain's
// start positions (one per vertex: the plan's capacity).
class RefineMemory {
 public:
  RefineMemory(std::size_t vertex_capacity, std::size_t triangle_capacity);
  // `storage` with the refinement spans set.
  session::SculptStorage attach(session::SculptStorage storage);

 private:
  meshio::RefinerBuffer refiner_;
  std::vector<session::TriangleChange> undo_triangles_;
  std::vector<float> chain_x_, chain_y_, chain_z_;  // a clutch chain's start (plan capacity)
};

}  // namespace twister::station_app
