// CommitRefinement: adaptive refinement at commit (docs/math.md §7, the paper's §6). When a
// stroke's warp becomes part of the model, edges whose midpoint error under the warp
// |(S(A) + S(B))/2 - S((A + B)/2)| exceeds the threshold are split (mesh::MeshRefiner:
// longest-edge bisection, conforming after every split) with S the plan's own warp
// in double precision (math::WarpPlan::warp_point) on rest positions, and the new
// vertices go where S takes their rest-pose midpoints. The refinement's topology
// (counts, rewritten and appended triangles, new vertices) joins the commit's undo
// entry. Live commits and journal replay both come through
// SessionHistory::apply_plan and the threshold the journal records, so the same
// journal on the same mesh (and capacity) refines to the same bits.
//
// Which commits refine (threshold_for): refinement on, storage for the mesh, and a
// plan that ends with this commit and was built for it (chain step 0). A freeze step
// keeps its plan's vertex set and weights for the next step, and a rebased plan's
// weights are no function warp_point can evaluate at a new point, so clutched
// strokes are not refined (docs/refinement.md).
// Capacity: the mesh's spare vertices and triangles (fixed at start). At a capacity
// the commit still applies, the refinement stops between two splits (conforming)
// and the report says which capacity (the session turns it into an event).
// Memory: the refiner's storage is the caller's (MeshRefinerStorage, sized for the
// mesh's capacities); no allocation. Not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>

#include "twister/journal/journal_record.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/mesh/mesh_refiner.hpp"
#include "twister/session/live_mesh.hpp"
#include "twister/session/undo_history.hpp"

namespace twister::session {

// The station's defaults (docs/refinement.md "Configuration" says why): refinement on,
// 0.5 mm, room for 100,000 more vertices (and twice as many triangles).
inline constexpr double kDefaultRefineThresholdM = 0.0005;
inline constexpr std::uint32_t kDefaultSpareVertices = 100'000;

struct RefineConfig {
  bool enabled = false;
  // Absolute, metres: the largest midpoint error an edge may keep. Not relative to
  // the radius: the deviation a sculptor sees on the model does not shrink with the
  // hand's ball (docs/refinement.md).
  double threshold_m = kDefaultRefineThresholdM;
  // Refine over the triangles the stroke's weights touch (and their conforming
  // closure) rather than the whole mesh: cost proportional to the stroke, recorded
  // as a version 4 stroke (docs/refinement.md "Local refinement").
  bool local = true;
};

// What one commit's refinement did.
struct RefineReport {
  bool ran = false;      // the commit was refined (threshold > 0)
  bool undoable = true;  // its topology fitted the undo history
  mesh::RefineResult result{};
};

// The lasting state for the operator and the display (SessionState::refine).
struct RefineStatus {
  bool enabled = false;    // configured on
  bool available = false;  // and storage for the mesh's capacity was given
  double threshold_m = 0.0;
  std::size_t spare_vertices = 0;  // capacity left in the mesh
  std::size_t spare_triangles = 0;
  std::uint64_t refined_commits = 0;
  std::uint64_t vertices_added = 0;  // by every refined commit so far (undo aside)
  std::uint64_t capacity_stops = 0;  // refined commits stopped by a capacity
  mesh::RefineStop last_stop = mesh::RefineStop::done;  // of the last refined commit
  std::uint32_t last_vertices_added = 0;
  std::uint32_t last_blocked = 0;  // edges over the threshold it could not split
};

class CommitRefinement {
 public:
  // `mesh` and the storage must outlive this object.
  CommitRefinement(LiveMesh& mesh, mesh::MeshRefinerStorage storage, const RefineConfig& config);
  CommitRefinement(const CommitRefinement&) = delete;
  CommitRefinement& operator=(const CommitRefinement&) = delete;

  // The threshold a commit of `stroke` refines with and records (0: not refined).
  double threshold_for(const journal::StrokeRecord& stroke, bool plan_goes_on) const;
  // The threshold the live preview refines to: the one a stroke's commit uses when
  // refinement is on and fits the mesh (0: commits are not refined).
  double live_threshold() const;

  // The storage fits the mesh's capacities: a threshold > 0 can be honoured.
  bool available() const { return refiner_.fits(mesh_.mesh()); }

  // The hook of a commit of `plan` (warped into the live columns from the mesh's
  // positions, which are not yet changed, the undo entry open): refines the rest mesh to `threshold_m`
  // (0 or not finite: nothing), places the new vertices and records the topology in
  // `undo`. A threshold > 0 needs available() (asserted).
  // `local`: mesh::MeshRefiner::refine_around the plan's vertices (else the whole mesh).
  RefineReport refine(const math::WarpPlan& plan, double threshold_m, UndoHistory& undo,
                      bool local = false);

  // New commits refine locally (RefineConfig::local).
  bool local() const { return config_.local; }

  RefineStatus status() const;

 private:
  LiveMesh& mesh_;
  mesh::MeshRefiner refiner_;
  RefineConfig config_;
  RefineStatus totals_{};
};

}  // namespace twister::session
