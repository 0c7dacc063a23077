// The station's one event vocabulary (issue 20): every kind carries the payload its
// accessors read, make_event refuses a mismatch, EventCounters counts from the kind and
// payload (a repeated commit once), EventQueue keeps the order and drops at capacity.
// Label architecture.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <utility>
#include <variant>

#include "twister/session/session_events.hpp"
#include "twister/station/event_queue.hpp"
#include "twister/station/station_counters.hpp"

namespace twister::station {
namespace {

using session::EventPayload;
using session::make_event;
using session::SessionEvent;
using session::SessionEventKind;
namespace payload = session::payload;

EventPayload default_payload(std::size_t index) {
  EventPayload p;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    ((I == index ? (p.emplace<I>(), 0) : 0), ...);
  }
  (std::make_index_sequence<std::variant_size_v<EventPayload>>{});
  return p;
}

SessionEvent sample(SessionEventKind kind, Status status = ok_status()) {
  return make_event(kind, 1, default_payload(session::payload_index(kind)), status);
}

TEST(SessionEventVocabulary, EveryKindHasANameAndAPayloadOfItsOwnType) {
  for (std::size_t k = 0; k < session::kSessionEventKindCount; ++k) {
    const auto kind = static_cast<SessionEventKind>(k);
    EXPECT_STRNE(session::session_event_kind_name(kind), "unknown") << k;
    EXPECT_LT(session::payload_index(kind), std::variant_size_v<EventPayload>);
    const SessionEvent e = sample(kind);
    EXPECT_EQ(e.kind, kind);
    EXPECT_EQ(e.payload.index(), session::payload_index(kind));
  }
}

TEST(SessionEventVocabulary, AccessorsReadTheTypedFields) {
  const SessionEvent c = make_event(SessionEventKind::committed, 1,
                                    payload::StrokeEnd{input::Reason::released, 42, true});
  EXPECT_EQ(c.stroke_end().reason, input::Reason::released);
  EXPECT_EQ(c.stroke_end().sequence, 42u);
  EXPECT_TRUE(c.stroke_end().repeat);
  const SessionEvent m =
      make_event(SessionEventKind::method_changed, 0, payload::Method{math::WarpMethod::scodef});
  EXPECT_EQ(m.method().method, math::WarpMethod::scodef);
  const SessionEvent r = make_event(
      SessionEventKind::command_refused, 0,
      payload::CommandRefusal{session::SessionCommandKind::redo, input::Reason::nothing_to_redo});
  EXPECT_EQ(r.command_refusal().command, session::SessionCommandKind::redo);
  EXPECT_EQ(r.command_refusal().reason, input::Reason::nothing_to_redo);
}

TEST(SessionEventVocabularyDeathTest, APayloadOfAnotherKindIsRefused) {
  EXPECT_DEATH((void)make_event(SessionEventKind::committed, 0, payload::Radius{0.5}), "");
  const SessionEvent e = make_event(SessionEventKind::undone, 0, payload::RecordRef{3});
  EXPECT_DEATH((void)e.stroke_end(), "");
}

TEST(EventCounters, EachKindCountsWhereTheSummaryReadsIt) {
  EventCounters c;
  c.count(sample(SessionEventKind::committed));
  c.count(make_event(SessionEventKind::committed, 0, payload::StrokeEnd{{}, 0, true}));
  c.count(sample(SessionEventKind::cancelled));
  c.count(sample(SessionEventKind::refused));
  c.count(sample(SessionEventKind::not_saved, StatusCode::io_error));
  c.count(make_event(SessionEventKind::not_saved, 0, payload::StrokeEnd{{}, 0, true},
                     StatusCode::io_error));
  c.count(sample(SessionEventKind::undone));
  c.count(sample(SessionEventKind::redone));
  c.count(sample(SessionEventKind::command_refused, StatusCode::io_error));
  c.count(sample(SessionEventKind::command_refused, StatusCode::failed_precondition));
  c.count(sample(SessionEventKind::refined));
  c.count(sample(SessionEventKind::refine_stopped, StatusCode::resource_exhausted));
  c.count(sample(SessionEventKind::checkpoint_written));
  c.count(sample(SessionEventKind::checkpoint_failed, StatusCode::io_error));
  EXPECT_EQ(c.strokes_committed, 1u);  // the repeat is the same commit
  EXPECT_EQ(c.strokes_cancelled, 1u);
  EXPECT_EQ(c.refused, 1u);
  EXPECT_EQ(c.strokes_not_saved, 1u);
  EXPECT_EQ(c.undos, 1u);
  EXPECT_EQ(c.redos, 1u);
  EXPECT_EQ(c.refined_commits, 1u);
  EXPECT_EQ(c.refine_stops, 1u);
  EXPECT_EQ(c.checkpoints_written, 1u);
  EXPECT_EQ(c.checkpoints_failed, 1u);
  EXPECT_EQ(c.journal_errors, 3u);  // not saved, undo not saved, checkpoint failed
}

TEST(EventCounters, TheOtherKindsCountNothing) {
  for (const SessionEventKind kind :
       {SessionEventKind::grab_begin,        SessionEventKind::tracking_lost,
        SessionEventKind::tracking_resumed,  SessionEventKind::radius_changed,
        SessionEventKind::radius_set,        SessionEventKind::move_begin,
        SessionEventKind::move_committed,    SessionEventKind::move_cancelled,
        SessionEventKind::history_overflow,  SessionEventKind::disengaged,
        SessionEventKind::engaged,           SessionEventKind::turn_limit_reached,
        SessionEventKind::turn_limit_left,   SessionEventKind::method_changed,
        SessionEventKind::symmetry_changed,  SessionEventKind::journal_recovered,
        SessionEventKind::tracker_streaming, SessionEventKind::tracker_lost,
        SessionEventKind::buttons_lost,      SessionEventKind::buttons_found}) {
    EventCounters c;
    c.count(sample(kind));
    const EventCounters zero;
    EXPECT_EQ(std::memcmp(&c, &zero, sizeof c), 0) << session::session_event_kind_name(kind);
  }
}

TEST(EventQueue, KeepsTheOrderAndDropsWhatDoesNotFit) {
  EventQueue q;
  for (std::uint32_t i = 0; i < EventQueue::kCapacity + 2; ++i) {
    const bool kept = q.push(make_event(SessionEventKind::undone, 0, payload::RecordRef{i}));
    EXPECT_EQ(kept, i < EventQueue::kCapacity);
  }
  for (std::uint32_t i = 0; i < EventQueue::kCapacity; ++i) {
    auto e = q.pop();
    ASSERT_TRUE(e.ok());
    EXPECT_EQ(e->record().sequence, i);
  }
  EXPECT_EQ(q.pop().status().code(), StatusCode::unavailable);
}

}  // namespace
}  // namespace twister::station
