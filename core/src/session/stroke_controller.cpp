#include "twister/session/stroke_controller.hpp"

#include <span>

namespace twister::session {
namespace {

std::uint8_t bit_of(std::uint8_t hand) { return static_cast<std::uint8_t>(1u << hand); }

}  // namespace

StrokeController::StrokeController(math::WarpPlan& plan, LiveMesh& mesh, const SessionPoses& poses,
                                   StrokeCommitSink& commits, math::WarpMethod method,
                                   const TurnConfig& turns)
    : plan_(plan),
      mesh_(mesh),
      poses_(poses),
      commits_(commits),
      method_(method),
      drives_{HandDrive(turns), HandDrive(turns)} {}

void StrokeController::begin_step(const input::ActionList& actions, float radius_m) {
  radius_m_ = radius_m;
  releasing_mask_ = 0;
  for (const input::Action& a : actions.items()) {
    if (a.kind == input::ActionKind::commit) releasing_mask_ |= bit_of(a.hand);
  }
}

void StrokeController::apply(const input::Action& action, SessionEvents& out) {
  const std::uint8_t bit = bit_of(action.hand);
  switch (action.kind) {
    case input::ActionKind::grab_begin:
      grab(action.hand, out);
      break;
    case input::ActionKind::freeze:
      if ((hand_mask_ & bit) == 0 || !drives_[action.hand].engaged()) return;
      freeze(action.hand, out);
      break;
    case input::ActionKind::unfreeze:
      if ((hand_mask_ & bit) == 0 || drives_[action.hand].engaged()) return;
      unfreeze(action.hand, out);
      break;
    case input::ActionKind::commit:
    case input::ActionKind::cancel:
      if ((hand_mask_ & bit) != 0) {
        end_grab(action.hand, action.kind == input::ActionKind::commit, action.reason, out);
      }
      break;
    default:
      return;
  }
  segment_moved_ = false;
}

void StrokeController::end_step(SessionEvents& out) {
  if (hand_mask_ == 0) return;
  update_plan(&out).ignore();  // on error the previous update stays in force
  segment_moved_ = true;
}

LiveWarp StrokeController::live() const {
  LiveWarp w;
  w.active = hand_mask_ != 0;
  w.hand_mask = hand_mask_;
  w.plan = &plan_;
  return w;
}

math::ConstVertexColumns StrokeController::live_positions() const {
  // The only CPU warp of a live stroke: asked for, never per tracker record.
  if (hand_mask_ != 0 && !live_current_) {
    live_current_ = plan_.apply(mesh_.rest(), mesh_.live()).ok();
  }
  return static_cast<const LiveMesh&>(mesh_).live();
}

void StrokeController::grab(std::uint8_t hand, SessionEvents& out) {
  const std::uint8_t bit = bit_of(hand);
  std::uint8_t mask = bit;
  drives_[hand].set_engaged(true);
  if (hand_mask_ != 0) {
    // A hand joins: what the other hand did so far is committed, then both continue
    // as one two-hand segment from the current poses. Hands grabbing in the same
    // step simply start together; a disengaged hand has nothing to commit.
    mask = static_cast<std::uint8_t>(mask | hand_mask_);
    if ((segment_moved_ || chain_step_ != 0) && segment_can_change()) {
      commit_segment(hand, input::Reason::none, out, input::Reason::none);
    }
    drop_segment();
  }
  const Status s = begin_segment(mask);
  if (s.ok()) {
    out.push(make_event(SessionEventKind::grab_begin, hand, {}, s));
    return;
  }
  out.push(make_event(SessionEventKind::refused, hand, payload::Reasoned{}, s));
  const auto previous = static_cast<std::uint8_t>(mask & ~bit);
  if (previous != 0) {
    const Status again = begin_segment(previous);
    if (!again.ok()) end_hands(previous, again, out);
  }
}

void StrokeController::freeze(std::uint8_t hand, SessionEvents& out) {
  const SessionEvent frozen = commit_segment(hand, input::Reason::none, out,
                                             input::Reason::released, /*plan_goes_on=*/true);
  if (!frozen.status.ok()) return end_not_saved(hand, frozen, out);
  // Restarted while still engaged: its start pose is where the hand is now, the point
  // its grabbed material went to; disengaged, it stays there (its anchor).
  restart_segment(true, out);
  if ((hand_mask_ & bit_of(hand)) == 0) return;
  drives_[hand].set_engaged(false);
  out.push(make_event(SessionEventKind::disengaged, hand, payload::RecordRef{last_sequence_}));
}

void StrokeController::unfreeze(std::uint8_t hand, SessionEvents& out) {
  // Since the last commit only another engaged hand can have warped anything. A
  // segment built while this hand was disengaged (chain step 0) is committed anyway:
  // its record keeps the poses its weights were built from, and the rebase below
  // becomes the next chain step, as a replay needs it.
  const bool commit = chain_step_ == 0 || (segment_can_change() && segment_moved_);
  if (commit) {
    const SessionEvent done = commit_segment(hand, input::Reason::none, out,
                                             input::Reason::released, /*plan_goes_on=*/true);
    if (!done.status.ok()) return end_not_saved(hand, done, out);
  }
  drives_[hand].set_engaged(true);
  restart_segment(commit, out);
  if ((hand_mask_ & bit_of(hand)) != 0) {
    out.push(make_event(SessionEventKind::engaged, hand));
  }
}

void StrokeController::end_not_saved(std::uint8_t hand, const SessionEvent& failed,
                                     SessionEvents& out) {
  // Not saved: the model is back at the last saved commit, so the chain cannot go on
  // (its next step would rebase a warp the model does not hold): the stroke ends for
  // every hand of the segment, each off the clutch. One commit was not made, however
  // many hands it ends (the others' events are repeats).
  const auto others = static_cast<std::uint8_t>(hand_mask_ & ~bit_of(hand));
  drop_segment();
  SessionEvent e = failed;
  payload::StrokeEnd again = failed.stroke_end();
  again.repeat = true;
  e.payload = again;
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    drives_[h].set_engaged(true);
    if ((others & bit_of(h)) == 0) continue;
    e.hand = h;
    out.push(e);
  }
}

void StrokeController::restart_segment(bool committed, SessionEvents& out) {
  plan_moved();
  const math::PlanFrames frames = start_drives();
  const Status rebased = plan_.rebase(frames);
  if (rebased.ok()) {
    if (committed) ++chain_step_;
    return;
  }
  // Cannot continue with the same weights: end the stroke cleanly.
  const std::uint8_t mask = hand_mask_;
  drop_segment();
  end_hands(mask, rebased, out);
}

void StrokeController::end_grab(std::uint8_t hand, bool commit, input::Reason cancel_reason,
                                SessionEvents& out) {
  auto remaining = static_cast<std::uint8_t>(hand_mask_ & ~bit_of(hand));
  if (commit) {
    SessionEvent committed;
    if (segment_can_change()) {
      committed = commit_segment(hand, input::Reason::released, out, input::Reason::released);
    } else {
      // Every hand is on the clutch: the freeze step before was the last commit.
      committed = make_event(SessionEventKind::committed, hand,
                             payload::StrokeEnd{input::Reason::released, last_sequence_, true});
      out.push(committed);
    }
    // The other hands of this segment released in the same step end with this very
    // commit (their own commit actions then find nothing open).
    const auto together = static_cast<std::uint8_t>(remaining & releasing_mask_);
    payload::StrokeEnd repeated = committed.stroke_end();
    repeated.repeat = true;
    committed.payload = repeated;
    for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
      if ((together & bit_of(h)) == 0) continue;
      committed.hand = h;
      drives_[h].set_engaged(true);
      out.push(committed);
    }
    remaining = static_cast<std::uint8_t>(remaining & ~together);
  } else {
    // tracking_timeout from the machine; stopped from cancel_open().
    out.push(make_event(SessionEventKind::cancelled, hand, payload::StrokeEnd{cancel_reason}));
  }
  drives_[hand].set_engaged(true);
  drop_segment();
  if (remaining == 0) return;
  const Status s = begin_segment(remaining);
  if (!s.ok()) end_hands(remaining, s, out);
}

Status StrokeController::begin_segment(std::uint8_t mask) {
  plan_moved();
  hand_mask_ = mask;
  const math::PlanFrames frames = start_drives();
  segment_radius_m_ = static_cast<double>(radius_m_);
  const Status s = plan_.build(mesh_.rest(), frames, segment_radius_m_, method_, symmetry_);
  if (!s.ok()) {
    drop_segment();
    return s;
  }
  chain_step_ = 0;
  return ok_status();  // no warp: live_positions() computes it when asked
}

SessionEvent StrokeController::commit_segment(std::uint8_t hand, input::Reason reason,
                                              SessionEvents& out, input::Reason reason_if_not_saved,
                                              bool plan_goes_on) {
  update_plan(&out).ignore();  // on error the previous update stays in force
  journal::StrokeRecord r;
  r.method = static_cast<std::uint8_t>(plan_.method());
  r.hand_mask = hand_mask_;
  r.chain_step = chain_step_;
  r.radius_m = segment_radius_m_;
  const math::SymmetrySpec sym = plan_.symmetry();
  r.symmetry = journal::StrokeSymmetry{static_cast<std::uint8_t>(sym.kind), sym.mirrors, sym.axis,
                                       sym.order};
  std::size_t i = 0;
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    if ((hand_mask_ & bit_of(h)) == 0) continue;
    r.start[h] = journal::as_stored(plan_.start_frame(i));
    r.end[h] = journal::as_stored(plan_.end_frame(i));
    if ((plan_.long_turns() & (1u << i)) != 0) r.long_turns |= bit_of(h);
    ++i;
  }
  const CommitOutcome done = commits_.commit(plan_, r, out, plan_goes_on);
  if (done.status.ok()) last_sequence_ = done.sequence;
  // A commit that did not happen (journal failure, plan error) is `not_saved`.
  const SessionEvent committed =
      done.status.ok()
          ? make_event(SessionEventKind::committed, hand, payload::StrokeEnd{reason, done.sequence},
                       done.status)
          : make_event(SessionEventKind::not_saved, hand,
                       payload::StrokeEnd{reason_if_not_saved, done.sequence}, done.status);
  out.push(committed);
  return committed;
}

bool StrokeController::segment_can_change() const {
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    if ((hand_mask_ & bit_of(h)) != 0 && drives_[h].engaged()) return true;
  }
  return false;
}

void StrokeController::end_hands(std::uint8_t mask, Status status, SessionEvents& out) {
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    if ((mask & bit_of(h)) == 0) continue;
    drives_[h].set_engaged(true);
    out.push(make_event(SessionEventKind::cancelled, h, payload::StrokeEnd{}, status));
  }
}

void StrokeController::drop_segment() {
  plan_moved();
  hand_mask_ = 0;
  plan_.reset();
}

Status StrokeController::update_plan(SessionEvents* out) {
  plan_moved();
  math::PlanFrames ends;
  std::uint8_t long_turns = 0;
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    if ((hand_mask_ & bit_of(h)) == 0) continue;
    HandDrive& drive = drives_[h];
    const TurnLimitChange change = drive.follow(poses_.hand_in_object(h));
    if (change != TurnLimitChange::none && out != nullptr) {
      const auto kind = change == TurnLimitChange::reached ? SessionEventKind::turn_limit_reached
                                                           : SessionEventKind::turn_limit_left;
      out->push(make_event(kind, h, payload::TurnLimit{drive.limit_rad()}));
    }
    if (drive.long_turn()) {
      long_turns = static_cast<std::uint8_t>(long_turns | (1u << ends.size()));
    }
    ends.push_back(drive.end_pose()).ignore();  // one per hand: cannot be full
  }
  const std::span<const math::Frame> end = ends;
  // Minimal: today's update, which keeps the stroke's axis sense at a half turn.
  // The screws only: no vertex is warped here (live_positions(), the commit).
  return drives_[0].config().tracking == TurnTracking::minimal
             ? plan_.update(end)
             : plan_.update_turns(end, long_turns);
}

math::PlanFrames StrokeController::start_drives() {
  math::PlanFrames frames;
  for (std::uint8_t h = 0; h < input::kHandCount; ++h) {
    if ((hand_mask_ & bit_of(h)) == 0) continue;
    // A disengaged hand keeps its anchor: its weights and its (identity) warp stay
    // where its material is, wherever the hand has gone on the clutch.
    if (drives_[h].engaged()) drives_[h].start(poses_.hand_in_object(h));
    frames.push_back(drives_[h].start_pose()).ignore();  // one per hand: cannot be full
  }
  return frames;
}

}  // namespace twister::session
