// Issue 23: buttons that come and go. A button device missing at start-up or
// vanishing later does not stop the station: one buttons_lost event (and the status
// the display shows), one buttons_found when it is back; a stroke whose buttons
// vanish ends the way a stroke ends on lost tracking (tracking_lost, the warp held,
// cancelled with tracking_timeout after lost_timeout: the model as before it), even
// when the device comes back in time or the clutch is in. Station over fakes (the
// station tests' fixture), virtual time.
#include "station_fixture.hpp"

namespace twister::station {
namespace {

using namespace test_fixture;  // NOLINT: the fixture's names

struct StrokeStep {
  SessionEventKind kind;
  input::Reason reason;
  bool operator==(const StrokeStep&) const = default;
};

// The stroke events of hand 1 (kind, and the reason where the payload has one).
std::vector<StrokeStep> stroke_steps(const std::vector<SessionEvent>& events) {
  std::vector<StrokeStep> out;
  for (const SessionEvent& e : events) {
    if (e.hand != 1) continue;
    switch (e.kind) {
      case SessionEventKind::grab_begin:
      case SessionEventKind::tracking_lost:
      case SessionEventKind::tracking_resumed:
        out.push_back({e.kind, input::Reason::none});
        break;
      case SessionEventKind::committed:
      case SessionEventKind::cancelled:
        out.push_back({e.kind, e.stroke_end().reason});
        break;
      default:
        break;
    }
  }
  return out;
}

int count(const std::vector<SessionEvent>& events, SessionEventKind kind) {
  int n = 0;
  for (const SessionEvent& e : events) n += e.kind == kind;
  return n;
}

const std::vector<StrokeStep> kLostStroke = {
    {SessionEventKind::grab_begin, input::Reason::none},
    {SessionEventKind::tracking_lost, input::Reason::none},
    {SessionEventKind::cancelled, input::Reason::tracking_timeout},
};

TEST_F(StationTest, MissingAtStartTheStationRunsSaysSoAndPicksItUp) {
  buttons_.set_connected(false);  // not plugged in at boot
  ASSERT_TRUE(station_.start().ok());
  run_until_streaming();
  run_ticks(60);
  std::vector<SessionEvent> seen = events();
  ASSERT_EQ(count(seen, SessionEventKind::buttons_lost), 1);
  for (const SessionEvent& e : seen) {
    if (e.kind == SessionEventKind::buttons_lost) {
      EXPECT_EQ(e.status.code(), StatusCode::unavailable);
    }
  }
  EXPECT_TRUE(station_.status().buttons_missing);
  EXPECT_EQ(station_.counters().input.button_errors, 0u);  // not polled while missing

  buttons_.fail(false);  // plugged in (the loop reopened it)
  run_ticks(2);
  seen = events();
  EXPECT_EQ(count(seen, SessionEventKind::buttons_found), 1);
  EXPECT_EQ(count(seen, SessionEventKind::buttons_lost), 0);
  EXPECT_FALSE(station_.status().buttons_missing);
  right_stroke({10.0f, 0.0f, 5.0f}, {12.0f, 1.0f, 5.0f});
  EXPECT_EQ(station_.counters().events.strokes_committed, 1u);
}

TEST_F(StationTest, ButtonsVanishingMidStrokeEndItAsLostTrackingDoes) {
  ASSERT_TRUE(station_.start().ok());
  run_until_streaming();
  right_stroke({10.0f, 0.0f, 5.0f}, {11.0f, 0.0f, 5.0f});
  ASSERT_EQ(station_.counters().events.strokes_committed, 1u);
  const std::uint64_t before = station_.mesh().checksum();
  (void)events();

  // The buttons' device is pulled in the middle of a drag.
  buttons_.press(3, true, clock_.now_us());
  run_ticks(3);
  right_in_ = {12.0f, 1.0f, 5.0f};
  run_ticks(3);
  buttons_.fail(true);
  const ports::TimestampUs vanished_us = clock_.now_us();
  run_ticks(1);
  EXPECT_TRUE(station_.status().buttons_missing);
  right_in_ = {20.0f, 5.0f, 5.0f};  // the hand goes on moving: the warp holds
  run_ticks(120);                   // 1 s: longer than lost_timeout (0.5 s)
  std::vector<SessionEvent> seen = events();
  EXPECT_EQ(stroke_steps(seen), kLostStroke);
  for (const SessionEvent& e : seen) {
    if (e.kind == SessionEventKind::cancelled) {
      const ports::TimestampUs after = e.time_us - vanished_us;
      EXPECT_GE(after, 500'000);
      EXPECT_LT(after, 520'000);  // at the lost timeout, give or take a tick
    }
  }
  EXPECT_EQ(count(seen, SessionEventKind::buttons_lost), 1);
  EXPECT_EQ(station_.counters().events.strokes_cancelled, 1u);
  EXPECT_EQ(station_.counters().events.strokes_committed, 1u);
  EXPECT_EQ(station_.mesh().checksum(), before);  // the model as before the stroke
  EXPECT_EQ(journal_records().size(), 1u);

  // The same stroke with the tracker unplugged instead: the same events.
  buttons_.fail(false);
  right_in_ = {12.0f, 1.0f, 5.0f};
  run_ticks(3);
  (void)events();
  buttons_.press(3, true, clock_.now_us());
  run_ticks(3);
  stream_.unplug();
  stream_.set_present(false);
  responder_.unplugged();
  run_ticks(120);
  EXPECT_EQ(stroke_steps(events()), kLostStroke);
  EXPECT_EQ(station_.mesh().checksum(), before);
}

TEST_F(StationTest, AStrokeWhoseButtonsVanishedIsCancelledEvenWhenTheyComeBackInTime) {
  ASSERT_TRUE(station_.start().ok());
  run_until_streaming();
  const std::uint64_t before = station_.mesh().checksum();
  (void)events();
  buttons_.press(3, true, clock_.now_us());
  run_ticks(3);
  right_in_ = {12.0f, 1.0f, 5.0f};
  run_ticks(3);
  buttons_.fail(true);
  run_ticks(12);         // 0.1 s without the device
  buttons_.fail(false);  // back; whether grab is still held is unknown
  run_ticks(120);
  const std::vector<SessionEvent> seen = events();
  EXPECT_EQ(stroke_steps(seen), kLostStroke);  // not resumed, not committed
  EXPECT_EQ(count(seen, SessionEventKind::buttons_found), 1);
  EXPECT_EQ(station_.mesh().checksum(), before);
  EXPECT_EQ(journal_records().size(), 0u);
  // The buttons work again, from released.
  right_stroke({10.0f, 0.0f, 5.0f}, {11.0f, 2.0f, 5.0f});
  EXPECT_EQ(station_.counters().events.strokes_committed, 1u);
}

TEST_F(StationTest, AClutchedStrokeWhoseButtonsVanishIsCancelledAfterTheTimeoutToo) {
  ASSERT_TRUE(station_.start().ok());
  run_until_streaming();
  buttons_.press(3, true, clock_.now_us());  // right grab
  run_ticks(3);
  right_in_ = {12.0f, 1.0f, 5.0f};
  run_ticks(3);
  buttons_.press(5, true, clock_.now_us());  // right freeze: committed, clutch in
  run_ticks(3);
  ASSERT_EQ(station_.status().clutch, 2);
  (void)events();
  buttons_.fail(true);
  run_ticks(120);
  const std::vector<SessionEvent> seen = events();
  const std::vector<StrokeStep> steps = stroke_steps(seen);
  ASSERT_FALSE(steps.empty());
  EXPECT_EQ(steps.back(), (StrokeStep{SessionEventKind::cancelled, input::Reason::tracking_timeout}));
  EXPECT_EQ(station_.status().clutch, 0);
  EXPECT_EQ(station_.counters().events.strokes_cancelled, 1u);
}

}  // namespace
}  // namespace twister::station
