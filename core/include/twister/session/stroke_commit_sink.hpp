// StrokeCommitSink: where a StrokeController's commits go. A commit makes the plan's
// current warp part of the model for good: the sink applies `plan` (built on the rest
// columns the controller was given) and records `stroke`, the segment's journal
// record without its sequence. `plan_goes_on`: the plan continues after the commit
// (a freeze step rebases it, same vertices and weights), so the commit must keep
// the mesh's vertex set. The session's sink is SessionHistory (mesh, undo entry,
// journal); commit-time work such as mesh refinement belongs behind this interface,
// not in the controller.
#pragma once

#include <cstdint>

#include "twister/base/status.hpp"
#include "twister/journal/journal_record.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/session/session_events.hpp"

namespace twister::session {

struct CommitOutcome {
  Status status{};             // not ok: nothing was committed (the plan could not apply,
                               // or io_error: its journal record could not be saved)
  std::uint32_t sequence = 0;  // the commit's journal sequence
};

class StrokeCommitSink {
 public:
  virtual ~StrokeCommitSink() = default;

  // Commits the plan's warp. Events of the commit itself (history_overflow) go to
  // `out`; the `committed` / `not_saved` event is the caller's.
  CommitOutcome commit(const math::WarpPlan& plan, const journal::StrokeRecord& stroke,
                       SessionEvents& out, bool plan_goes_on = false) {
    return do_commit(plan, stroke, out, plan_goes_on);
  }

 private:
  virtual CommitOutcome do_commit(const math::WarpPlan& plan, const journal::StrokeRecord& stroke,
                                  SessionEvents& out, bool plan_goes_on) = 0;
};

}  // namespace twister::session
