// Station over fakes: a scripted Fastrak responder on a FakeByteStream (answers `S`,
// streams records after `C`), scripted button edges, FakeStorage, virtual time.
#include "station_fixture.hpp"

namespace twister::station {
namespace {

using namespace test_fixture;  // NOLINT: the fixture's names

TEST_F(StationTest, PollBeforeStartIsRefused) {
  EXPECT_EQ(station_.poll().code(), StatusCode::failed_precondition);
}

TEST_F(StationTest, StrokeIsCommittedToTheJournalWithItsPoses) {
  ASSERT_TRUE(station_.start().ok());
  const std::uint64_t before = station_.mesh().checksum();
  run_until_streaming();
  right_stroke({10.0f, 0.0f, 5.0f}, {12.0f, 1.0f, 5.0f});
  EXPECT_EQ(station_.counters().events.strokes_committed, 1u);
  const auto records = journal_records();
  ASSERT_EQ(records.size(), 1u);
  const auto& s = records[0].stroke;
  EXPECT_EQ(records[0].type, journal::RecordType::stroke);
  EXPECT_EQ(records[0].sequence, 0u);
  EXPECT_EQ(s.hand_mask, 2);
  EXPECT_NEAR(s.start[1].origin.x, 10.0 * kInch, 1e-6);
  EXPECT_NEAR(s.end[1].origin.x, 12.0 * kInch, 1e-6);
  EXPECT_NEAR(s.end[1].origin.y, 1.0 * kInch, 1e-6);
  bool saw_commit = false;
  for (const auto& e : events()) {
    saw_commit |= e.kind == SessionEventKind::committed && e.hand == 1;
  }
  EXPECT_TRUE(saw_commit);
  EXPECT_NE(station_.mesh().checksum(), before);  // the stroke warped the model
}

// What the display link reports: the session's clutch, the angle turned in the open
// stroke against its limit, the method; the tracker state and rate.
TEST_F(StationTest, StatusCarriesTheClutchAndTheTurnAgainstItsLimit) {
  ASSERT_TRUE(station_.start().ok());
  run_until_streaming();
  run_ticks(250);  // a full rate window after the start-up
  StationStatus st = station_.status();
  EXPECT_EQ(st.tracker, TrackerLinkState::streaming);
  EXPECT_NEAR(st.tracker_rate_hz, 2 * 120.0, 10.0);  // both hands at the tick rate
  EXPECT_EQ(st.clutch, 0);
  EXPECT_NEAR(st.turn_limit_rad, 330.0 * std::numbers::pi / 180.0, 1e-5);
  EXPECT_EQ(st.method, math::WarpMethod::twister);
  buttons_.press(3, true, clock_.now_us());  // right grab
  run_ticks(3);
  for (int k = 1; k <= 6; ++k) {  // 60 degrees about z in 10-degree samples
    const double half = 0.5 * (10.0 * k) * std::numbers::pi / 180.0;
    right_q_ = {static_cast<float>(std::cos(half)), 0.0f, 0.0f, static_cast<float>(std::sin(half))};
    run_ticks(1);
  }
  st = station_.status();
  EXPECT_NEAR(st.turned_rad, std::numbers::pi / 3.0, 1e-3);
  EXPECT_EQ(st.clutch, 0);
  buttons_.press(5, true, clock_.now_us());  // right freeze: the clutch is in
  run_ticks(3);
  EXPECT_EQ(station_.status().clutch, 2);
  buttons_.press(5, false, clock_.now_us());
  run_ticks(3);
  EXPECT_EQ(station_.status().clutch, 0);
  buttons_.press(3, false, clock_.now_us());
  run_ticks(3);
  st = station_.status();
  EXPECT_EQ(st.turned_rad, 0.0f);  // no open stroke
  EXPECT_EQ(st.strokes_committed, station_.counters().events.strokes_committed);
  EXPECT_EQ(st.capacity_stops, 0u);
}

TEST_F(StationTest, UnplugMidStrokeCancelsItAndReplugContinues) {
  ASSERT_TRUE(station_.start().ok());
  run_until_streaming();
  right_stroke({10.0f, 0.0f, 5.0f}, {11.0f, 0.0f, 5.0f});
  ASSERT_EQ(station_.counters().events.strokes_committed, 1u);

  // Grab, then the cable is pulled in the middle of the drag.
  buttons_.press(3, true, clock_.now_us());
  run_ticks(3);
  stream_.unplug();
  stream_.set_present(false);
  responder_.unplugged();
  right_in_ = {30.0f, 30.0f, 30.0f};  // where the hand goes while untracked
  run_ticks(120);                     // 1 s: longer than lost_timeout (0.5 s)
  buttons_.press(3, false, clock_.now_us());
  run_ticks(3);
  EXPECT_FALSE(station_.tracker_session().streaming());
  EXPECT_EQ(station_.counters().events.strokes_cancelled, 1u);
  EXPECT_EQ(station_.counters().events.strokes_committed, 1u);

  // Plugged back: the session re-initialises and the next stroke commits.
  stream_.set_present(true);
  run_until_streaming();
  right_stroke({20.0f, 0.0f, 5.0f}, {21.0f, 2.0f, 5.0f});
  EXPECT_EQ(station_.counters().events.strokes_committed, 2u);

  const auto records = journal_records();
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].sequence, 1u);
  EXPECT_NEAR(records[1].stroke.start[1].origin.x, 20.0 * kInch, 1e-6);
  EXPECT_NEAR(records[1].stroke.end[1].origin.y, 2.0 * kInch, 1e-6);
  for (const auto& r : records) {  // no record carries the untracked position
    EXPECT_LT(r.stroke.end[1].origin.z, 10.0 * kInch);
  }
  int lost = 0;
  int streaming = 0;
  for (const auto& e : events()) {
    lost += e.kind == SessionEventKind::tracker_lost;
    streaming += e.kind == SessionEventKind::tracker_streaming;
  }
  EXPECT_EQ(lost, 1);
  EXPECT_EQ(streaming, 2);
}

TEST_F(StationTest, StylusSwitchDrivesItsConfiguredButtonLine) {
  config_.stylus_line[0] = 0;  // station 1's stylus = line 0 = hand 0 grab (paper map)
  auto mesh = initial_mesh();
  auto work = std::make_unique<TestWork>();
  Station station(stream_, buttons_, clock_, storage_, *mesh, work->spans(), config_);
  // Drive this station instead of the fixture's.
  auto tick = [&](int n) {
    for (int i = 0; i < n; ++i) {
      responder_.service();
      responder_.emit(1, left_in_, stylus_);
      responder_.emit(2, right_in_, false, right_q_);
      ASSERT_TRUE(station.poll().ok());
      responder_.service();
      clock_.advance_us(8'333);
    }
  };
  ASSERT_TRUE(station.start().ok());
  for (int i = 0; i < 500 && !station.tracker_session().streaming(); ++i) tick(1);
  ASSERT_TRUE(station.tracker_session().streaming());
  tick(3);
  stylus_ = true;
  tick(3);
  left_in_ = {-8.0f, 1.0f, 5.0f};
  tick(3);
  stylus_ = false;
  tick(3);
  EXPECT_EQ(station.counters().events.strokes_committed, 1u);
  const auto records = journal_records();
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].stroke.hand_mask, 1);
  EXPECT_NEAR(records[0].stroke.start[0].origin.x, -10.0 * kInch, 1e-6);
  EXPECT_NEAR(records[0].stroke.end[0].origin.x, -8.0 * kInch, 1e-6);
}

TEST_F(StationTest, RestartContinuesTheJournalAfterATornTail) {
  ASSERT_TRUE(station_.start().ok());
  run_until_streaming();
  right_stroke({10.0f, 0.0f, 5.0f}, {12.0f, 0.0f, 5.0f});
  ASSERT_EQ(journal_records().size(), 1u);
  // Power cut in the middle of the next append: half a record lands on disk.
  const std::array<std::byte, 7> torn{std::byte{40}, std::byte{0}, std::byte{0}, std::byte{0},
                                      std::byte{1},  std::byte{1}, std::byte{0}};
  ASSERT_TRUE(storage_.append(torn).ok());

  test::FakeByteStream stream2;
  auto mesh2 = initial_mesh();
  auto work2 = std::make_unique<TestWork>();
  Station restarted(stream2, buttons_, clock_, storage_, *mesh2, work2->spans(), config_);
  ASSERT_TRUE(restarted.start().ok());
  EXPECT_EQ(restarted.journal_records(), 1u);
  // Replay rebuilt exactly the mesh the first run committed.
  EXPECT_EQ(restarted.mesh().checksum(), station_.mesh().checksum());
  auto e = restarted.next_event();
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->kind, SessionEventKind::journal_recovered);
  EXPECT_EQ(e->journal_recovered().torn_tail_bytes, torn.size());
  EXPECT_EQ(journal_records().size(), 1u);
}

TEST_F(StationTest, NotAJournalIsRefused) {
  const std::array<std::byte, 12> junk{std::byte{'h'}, std::byte{'e'}, std::byte{'l'},
                                       std::byte{'l'}, std::byte{'o'}};
  storage_.load(junk);
  EXPECT_EQ(station_.start().code(), StatusCode::data_loss);
}

TEST_F(StationTest, ButtonSourceFailureIsReportedOnce) {
  ASSERT_TRUE(station_.start().ok());
  buttons_.fail(true);
  run_ticks(5);
  int reports = 0;
  for (const auto& e : events()) {
    if (e.kind != SessionEventKind::buttons_lost) continue;
    ++reports;
    EXPECT_EQ(e.status.code(), StatusCode::io_error);
  }
  EXPECT_EQ(reports, 1);
  // Not polled while it is not connected: one error, then silence until it is back.
  EXPECT_EQ(station_.counters().input.button_errors, 1u);
  EXPECT_TRUE(station_.status().buttons_missing);
}

TEST_F(StationTest, PollDoesNotAllocateWhileStreamingAndCommitting) {
  ASSERT_TRUE(station_.start().ok());
  run_until_streaming();
  auto stroke = [&] {
    buttons_.press(3, true, clock_.now_us());
    run_ticks(5);
    right_in_ = {11.0f, 1.0f, 5.0f};
    run_ticks(5);
    buttons_.press(3, false, clock_.now_us());
    run_ticks(5);
  };
  EXPECT_NO_ALLOCATIONS(stroke());
  EXPECT_EQ(station_.counters().events.strokes_committed, 1u);
}

}  // namespace
}  // namespace twister::station
