#include "twister/input/stroke_controller.hpp"

#include <span>

#include "twister/input/journal_pose.hpp"

namespace twister::input {

StrokeController::StrokeController(math::WarpPlan& plan, LiveMesh& mesh, const SessionPoses& poses,
                                   StrokeCommitSink& commits, math::WarpMethod method)
    : plan_(plan), mesh_(mesh), poses_(poses), commits_(commits), method_(method) {}

void StrokeController::begin_step(const ActionList& actions, float radius_m) {
  radius_m_ = radius_m;
  releasing_mask_ = 0;
  for (const Action& a : actions.items()) {
    if (a.kind == ActionKind::commit) releasing_mask_ |= static_cast<std::uint8_t>(1u << a.hand);
  }
}

void StrokeController::apply(const Action& action, SessionEvents& out) {
  const auto bit = static_cast<std::uint8_t>(1u << action.hand);
  switch (action.kind) {
    case ActionKind::grab_begin:
      grab(action.hand, out);
      break;
    case ActionKind::freeze:
      if ((hand_mask_ & bit) == 0) return;
      freeze(action.hand, out);
      break;
    case ActionKind::commit:
    case ActionKind::cancel:
      if ((hand_mask_ & bit) != 0) end_grab(action.hand, action.kind == ActionKind::commit, out);
      break;
    default:
      return;
  }
  segment_moved_ = false;
}

void StrokeController::end_step() {
  if (hand_mask_ == 0) return;
  update_plan().ignore();  // on error the previous update stays in force
  segment_moved_ = true;
}

LiveWarp StrokeController::live() const {
  LiveWarp w;
  w.active = hand_mask_ != 0;
  w.hand_mask = hand_mask_;
  w.plan = &plan_;
  w.positions = static_cast<const LiveMesh&>(mesh_).live();
  return w;
}

void StrokeController::grab(std::uint8_t hand, SessionEvents& out) {
  const auto bit = static_cast<std::uint8_t>(1u << hand);
  std::uint8_t mask = bit;
  if (hand_mask_ != 0) {
    // A hand joins: what the other hand did so far is committed, then both continue
    // as one two-hand segment from the current poses. Hands grabbing in the same
    // step simply start together.
    mask = static_cast<std::uint8_t>(mask | hand_mask_);
    if (segment_moved_ || chain_step_ != 0) commit_segment(hand, Reason::none, out, Reason::none);
    drop_segment();
  }
  const Status s = begin_segment(mask);
  if (s.ok()) {
    out.push({SessionEventKind::grab_begin, hand, Reason::none, s, 0});
    return;
  }
  out.push({SessionEventKind::refused, hand, Reason::none, s, 0});
  const auto previous = static_cast<std::uint8_t>(mask & ~bit);
  if (previous != 0) {
    const Status again = begin_segment(previous);
    if (!again.ok()) end_hands(previous, again, out);
  }
}

void StrokeController::freeze(std::uint8_t hand, SessionEvents& out) {
  const SessionEvent frozen = commit_segment(hand, Reason::none, out, Reason::released);
  if (!frozen.status.ok()) {
    // Not saved: the model is back at the last saved commit, so the chain cannot go
    // on (its next step would rebase a warp the model does not hold): the stroke ends
    // for every hand of the segment.
    const auto others = static_cast<std::uint8_t>(hand_mask_ & ~(1u << hand));
    drop_segment();
    for (std::uint8_t h = 0; h < kHandCount; ++h) {
      if ((others & (1u << h)) == 0) continue;
      SessionEvent e = frozen;
      e.hand = h;
      out.push(e);
    }
    return;
  }
  std::array<math::Frame, 2> frames{};
  const std::size_t n = plan_frames(frames);
  const Status rebased = plan_.rebase(std::span(frames).first(n));
  if (rebased.ok()) {
    segment_start_ = frames;
    ++chain_step_;
    return;
  }
  // Cannot continue with the same weights: end the stroke cleanly.
  const std::uint8_t mask = hand_mask_;
  drop_segment();
  end_hands(mask, rebased, out);
}

void StrokeController::end_grab(std::uint8_t hand, bool commit, SessionEvents& out) {
  auto remaining = static_cast<std::uint8_t>(hand_mask_ & ~(1u << hand));
  if (commit) {
    SessionEvent committed = commit_segment(hand, Reason::released, out, Reason::released);
    // The other hands of this segment released in the same step end with this very
    // commit (their own commit actions then find nothing open).
    const auto together = static_cast<std::uint8_t>(remaining & releasing_mask_);
    for (std::uint8_t h = 0; h < kHandCount; ++h) {
      if ((together & (1u << h)) == 0) continue;
      committed.hand = h;
      out.push(committed);
    }
    remaining = static_cast<std::uint8_t>(remaining & ~together);
  } else {
    out.push({SessionEventKind::cancelled, hand, Reason::tracking_timeout, ok_status(), 0});
  }
  drop_segment();
  if (remaining == 0) return;
  const Status s = begin_segment(remaining);
  if (!s.ok()) end_hands(remaining, s, out);
}

Status StrokeController::begin_segment(std::uint8_t mask) {
  hand_mask_ = mask;
  std::array<math::Frame, 2> frames{};
  const std::size_t n = plan_frames(frames);
  segment_radius_m_ = static_cast<double>(radius_m_);
  const Status s =
      plan_.build(mesh_.rest(), std::span(frames).first(n), segment_radius_m_, method_);
  if (!s.ok()) {
    drop_segment();
    return s;
  }
  chain_step_ = 0;
  segment_start_ = frames;
  return plan_.apply(mesh_.rest(), mesh_.live());
}

SessionEvent StrokeController::commit_segment(std::uint8_t hand, Reason reason, SessionEvents& out,
                                              Reason reason_if_not_saved) {
  update_plan().ignore();  // on error the previous update stays in force
  journal::StrokeRecord r;
  r.method = static_cast<std::uint8_t>(plan_.method());
  r.hand_mask = hand_mask_;
  r.chain_step = chain_step_;
  r.radius_m = segment_radius_m_;
  std::size_t i = 0;
  for (std::uint8_t h = 0; h < kHandCount; ++h) {
    if ((hand_mask_ & (1u << h)) == 0) continue;
    r.start[h] = to_journal(segment_start_[i]);
    r.end[h] = to_journal(plan_.end_frame(i));
    ++i;
  }
  const CommitOutcome done = commits_.commit(plan_, r, out);
  // A commit that did not happen (journal failure, plan error) is `not_saved`.
  const SessionEvent committed =
      done.status.ok()
          ? SessionEvent{SessionEventKind::committed, hand, reason, done.status, done.sequence}
          : SessionEvent{SessionEventKind::not_saved, hand, reason_if_not_saved, done.status,
                         done.sequence};
  out.push(committed);
  return committed;
}

void StrokeController::end_hands(std::uint8_t mask, Status status, SessionEvents& out) {
  for (std::uint8_t h = 0; h < kHandCount; ++h) {
    if ((mask & (1u << h)) != 0)
      out.push({SessionEventKind::cancelled, h, Reason::none, status, 0});
  }
}

void StrokeController::drop_segment() {
  hand_mask_ = 0;
  plan_.reset();
}

Status StrokeController::update_plan() {
  std::array<math::Frame, 2> frames{};
  const std::size_t n = plan_frames(frames);
  TWISTER_TRY(plan_.update(std::span(frames).first(n)));
  return plan_.apply(mesh_.rest(), mesh_.live());
}

std::size_t StrokeController::plan_frames(std::array<math::Frame, 2>& frames) const {
  std::size_t n = 0;
  for (std::uint8_t h = 0; h < kHandCount; ++h) {
    if ((hand_mask_ & (1u << h)) != 0) frames[n++] = poses_.hand_in_object(h);
  }
  return n;
}

}  // namespace twister::input
