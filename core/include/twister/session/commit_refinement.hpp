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
// plan that ends with this commit. A freeze step (the plan goes on) is never refined:
// the next step keeps its vertex set and weights. A clutch chain is refined once, at
// the commit that ends it (chain step > 0), with the chain's combined warp C on the
// chain-start positions (ClutchChain, ChainWarp): the old vertices keep exactly the
// positions the unrefined chain gives them, the new ones go to C(rest midpoint).
// Chains longer than kMaxChainSteps, scodef chains and chains this object did not see
// begin are committed unrefined (docs/refinement.md "Clutch chains").
// Capacity: the mesh's spare vertices and triangles (fixed at start). At a capacity
// the commit still applies, the refinement stops between two splits (conforming)
// and the report says which capacity (the session turns it into an event).
// Memory: the refiner's storage is the caller's (MeshRefinerStorage, sized for the
// mesh's capacities); no allocation. Not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/journal/journal_record.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/mesh/mesh_refiner.hpp"
#include "twister/mesh/point_warp.hpp"
#include "twister/session/clutch_chain.hpp"
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
  std::uint32_t last_blocked = 0;     // edges over the threshold it could not split
  std::uint64_t refined_chains = 0;   // clutch chains refined at their end
  std::uint64_t chains_too_long = 0;  // chains ended unrefined: over kMaxChainSteps
};

class CommitRefinement {
 public:
  // `mesh` and the storage must outlive this object. `chain_start`: ClutchChain's
  // columns (plan capacity; empty: clutch chains are committed unrefined).
  CommitRefinement(LiveMesh& mesh, mesh::MeshRefinerStorage storage, const RefineConfig& config,
                   math::VertexColumns chain_start = {});
  CommitRefinement(const CommitRefinement&) = delete;
  CommitRefinement& operator=(const CommitRefinement&) = delete;

  // The threshold a live commit of `plan` as `stroke` refines with and records (0: not
  // refined). Asked before the commit's note_commit().
  double threshold_for(const math::WarpPlan& plan, const journal::StrokeRecord& stroke,
                       bool plan_goes_on) const;
  // Whether a replayed record's refined chain end can be reproduced (the chain was
  // seen from its step 0, within kMaxChainSteps, not scodef).
  bool chain_refinable(const math::WarpPlan& plan, std::uint16_t chain_step) const {
    return chain_.refinable(plan, chain_step, mesh_.mesh());
  }
  // Every commit of a plan, before it changes the mesh: the clutch chain's bookkeeping.
  // `keep_chain`: a step-0 commit keeps the chain's start (live: its plan goes on and
  // refinement is on; replay: not refined, so a chain may follow).
  void note_commit(const math::WarpPlan& plan, std::uint16_t chain_step, bool keep_chain) {
    chain_.note(plan, chain_step, keep_chain, mesh_.mesh());
  }
  // A live chain ended with an unrefined commit although refinement is on: counted
  // when it was too long (after its note_commit()).
  void chain_ended_unrefined();
  // An undo, redo or restored checkpoint: no chain continues across it.
  void forget_chain() { chain_.forget(); }
  // The threshold the live preview refines to: the one a stroke's commit uses when
  // refinement is on and fits the mesh (0: commits are not refined).
  double live_threshold() const;

  // The storage fits the mesh's capacities: a threshold > 0 can be honoured.
  bool available() const { return refiner_.fits(mesh_.mesh()); }

  // The hook of a commit of `plan` (warped into the live columns from the mesh's
  // positions, which are not yet changed, the undo entry open): refines the rest mesh to
  // `threshold_m` (0 or not finite: nothing), places the new vertices and records the topology in
  // `undo`. A threshold > 0 needs available() (asserted).
  // `local`: mesh::MeshRefiner::refine_around the plan's vertices (else the whole mesh).
  RefineReport refine(const math::WarpPlan& plan, double threshold_m, UndoHistory& undo,
                      bool local = false);
  // The same for the commit that ends a clutch chain (after its note_commit(), with
  // chain_refinable()): the plan's vertices are put back at the chain's start, the
  // mesh is refined under the chain's warp C and the new vertices placed at C of their
  // rest midpoint. The plan's vertices are left at the chain's start: the caller
  // records their undo changes before and places them after (the live columns).
  RefineReport refine_chain(const math::WarpPlan& plan, double threshold_m, UndoHistory& undo,
                            bool local = false);

  // New commits refine locally (RefineConfig::local).
  bool local() const { return config_.local; }

  RefineStatus status() const;

 private:
  // `images`: S in float of `vertices` when the caller has it (mesh::VertexImages).
  RefineReport refine_with(const mesh::PointWarp& warp, std::span<const std::uint32_t> vertices,
                           double threshold_m, UndoHistory& undo, bool local,
                           mesh::VertexImages images);

  LiveMesh& mesh_;
  mesh::MeshRefiner refiner_;
  RefineConfig config_;
  RefineStatus totals_{};
  ClutchChain chain_;
};

}  // namespace twister::session
