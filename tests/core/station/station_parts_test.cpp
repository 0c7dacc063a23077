// Station's parts alone and together (issue 20): TrackerHands without a session, and
// every session event reaching the station's queue stamped and counted.
#include "station_fixture.hpp"

namespace twister::station {
namespace {

using namespace test_fixture;  // NOLINT: the fixture's names

// TrackerHands alone (no session): the tracker coming up is one event, poses reach
// the hand holding their receiver, the stylus switch becomes button edges.
TEST(TrackerHands, StreamingHandPosesAndTheStylusWithoutASession) {
  test::FakeByteStream stream;
  test::FakeClock clock;
  StationConfig config = test_config();
  config.stylus_line = {4, -1, -1, -1};
  FastrakResponder responder(stream, config.session.protocol);
  TrackerHands hands(stream, clock, config);
  InputCounters counters;
  std::vector<SessionEvent> changes;
  std::vector<ports::ButtonEdge> edges;
  for (int i = 0; i < 600; ++i) {
    responder.service();
    responder.emit(1, {20.0f, 0.0f, 5.0f}, /*stylus=*/i >= 500);
    StylusEdges stylus;
    if (auto change = hands.drain(clock.now_us(), stylus, counters)) changes.push_back(*change);
    for (const ports::ButtonEdge& e : stylus.items()) edges.push_back(e);
    clock.advance_us(8'333);
  }
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0].kind, SessionEventKind::tracker_streaming);
  EXPECT_EQ(changes[0].tracker_streaming().start_ups, 1u);
  EXPECT_EQ(hands.link_state(), TrackerLinkState::streaming);
  EXPECT_TRUE(hands.hand_valid(0, clock.now_us()));
  EXPECT_FALSE(hands.hand_valid(1, clock.now_us()));  // receiver 2 sent nothing
  EXPECT_NEAR(hands.hand_pose(0).origin.x, 20.0 * 0.0254, 1e-6);
  EXPECT_GT(counters.poses, 0u);
  EXPECT_EQ(counters.pose_errors, 0u);
  ASSERT_EQ(edges.size(), 1u);
  EXPECT_EQ(edges[0].line, 4);
  EXPECT_TRUE(edges[0].pressed);
  EXPECT_EQ(counters.button_edges, 1u);
}

// Every event the session reports reaches the station's queue unchanged, stamped
// with the poll's time, and the counters count it.
TEST_F(StationTest, EverySessionEventReachesTheQueueStampedAndCounted) {
  ASSERT_TRUE(station_.start().ok());
  run_until_streaming();
  (void)events();
  right_stroke({10.0f, 0.0f, 5.0f}, {12.0f, 0.0f, 5.0f});
  std::uint64_t commits = 0;
  bool grabbed = false;
  for (const SessionEvent& e : events()) {
    EXPECT_GT(e.time_us, 0u) << session::session_event_kind_name(e.kind);
    grabbed |= e.kind == SessionEventKind::grab_begin && e.hand == 1;
    if (e.kind == SessionEventKind::committed && !e.stroke_end().repeat) ++commits;
  }
  EXPECT_TRUE(grabbed);
  EXPECT_EQ(commits, 1u);
  EXPECT_EQ(station_.counters().events.strokes_committed, commits);
}

}  // namespace
}  // namespace twister::station
