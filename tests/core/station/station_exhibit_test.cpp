// Exhibit mode through the Station (issue 25): a visitor's first grab begins the
// sculpture, idle or the chord ends it, the grace undoes it, the archive gets the
// whole journal and the final model, the journal rotates (a new identity, records
// from 0) and the model is the base again; a failed archive (full disk) changes
// nothing and is retried; the display's commands; exhibit mode off changes nothing;
// no heap in the loop. Label exhibit.
#include <vector>

#include "fakes/fake_link_listener.hpp"
#include "fakes/memory_wire.hpp"
#include "station_fixture.hpp"
#include "twister/station/station_link.hpp"

namespace twister::station {
namespace {

using namespace test_fixture;  // NOLINT: the fixture's names
using session::VisitorNote;
using session::VisitorPhase;

constexpr ports::TimestampUs kS = 1'000'000;

// In memory: what archive() got, or a full disk.
class FakeArchive final : public SculptureArchive {
 public:
  struct Entry {
    SculptureSummary summary;
    std::vector<std::byte> journal;
    std::uint64_t checksum = 0;
  };
  std::vector<Entry> entries;
  bool full = false;
  std::uint32_t next_id = 0x5C000001;
  std::size_t allocations = 0;  // the fake's own (one journal copy per archive)

 private:
  ArchiveOutcome do_archive(const SculptureSummary& s, ports::Storage& journal, std::uint64_t bytes,
                            const mesh::Mesh& mesh, const Pose& /*object_pose*/) override {
    if (full) return {StatusCode::io_error, true};
    Entry e{s, std::vector<std::byte>(bytes), mesh.checksum()};
    ++allocations;
    auto n = journal.read_at(0, e.journal);
    if (!n.ok() || *n != bytes) return {StatusCode::io_error, false};
    entries.push_back(std::move(e));
    return {};
  }
  std::uint32_t do_next_journal_id() override { return next_id++; }
};

StationConfig exhibit_config(bool on) {
  StationConfig c = exhibit_test_config();
  c.exhibit.visitor.enabled = on;
  return c;
}

class ExhibitStation : public ::testing::Test {
 protected:
  explicit ExhibitStation(bool on = true) : ExhibitStation(exhibit_config(on)) {}
  explicit ExhibitStation(const StationConfig& config)
      : config_(config),
        responder_(stream_, config_.session.protocol),
        mesh_(grid()),
        base_(grid()),
        station_(stream_, buttons_, clock_, storage_, *mesh_, work_->spans(), config_,
                 StationFiles{nullptr, nullptr, nullptr, 0x5B000001, &archive_, base_.get(), 4}) {}

  static std::unique_ptr<TestMesh> grid() {
    auto m = std::make_unique<TestMesh>();
    make_grid(*m);
    return m;
  }
  void run_ticks(int n) {
    for (int i = 0; i < n; ++i) {
      responder_.service();
      responder_.emit(1, left_in_, false);
      responder_.emit(2, right_in_, false);
      ASSERT_TRUE(station_.poll().ok());
      responder_.service();
      clock_.advance_us(8'333);
    }
  }
  void run_seconds(double s) { run_ticks(static_cast<int>(s * 120.0)); }
  void start() {
    ASSERT_TRUE(station_.start().ok());
    for (int i = 0; i < 500 && !station_.tracker_session().streaming(); ++i) run_ticks(1);
    ASSERT_TRUE(station_.tracker_session().streaming());
    run_ticks(3);
  }
  void right_stroke(float dx) {
    right_in_ = {10.0f, 0.0f, 5.0f};
    run_ticks(2);
    buttons_.press(3, true, clock_.now_us());
    run_ticks(3);
    right_in_ = {10.0f + dx, 1.0f, 5.0f};
    run_ticks(3);
    buttons_.press(3, false, clock_.now_us());
    run_ticks(3);
  }
  void chord(bool held) {
    buttons_.press(kLeftRadius, held, clock_.now_us());
    buttons_.press(kRightFreeze, held, clock_.now_us());
  }
  std::vector<VisitorNote> notes() {
    std::vector<VisitorNote> out;
    for (auto e = station_.next_event(); e.ok(); e = station_.next_event()) {
      if (e->kind == SessionEventKind::visitor) {
        out.push_back(e->visitor().note);
        last_note_ = e->visitor();
      }
    }
    return out;
  }
  session::payload::Visitor last_note_{};
  std::uint32_t journal_id() {
    journal::JournalReader reader(storage_);
    EXPECT_TRUE(reader.open().ok());
    return reader.format().id;
  }

  StationConfig config_;
  test::FakeByteStream stream_;
  test::FakeClock clock_{1'000'000};
  test::FakeStorageWithStorage<> storage_;
  test::FakeButtonSource buttons_;
  FastrakResponder responder_;
  std::unique_ptr<TestMesh> mesh_;
  std::unique_ptr<TestMesh> base_;
  std::unique_ptr<TestWork> work_ = std::make_unique<TestWork>();
  FakeArchive archive_;
  Station station_;
  std::array<float, 3> left_in_{-10.0f, 0.0f, 5.0f};
  std::array<float, 3> right_in_{10.0f, 0.0f, 5.0f};
};

TEST_F(ExhibitStation, IdleEndsTheGraceArchivesTheJournalRotatesAndTheModelIsTheBase) {
  start();
  EXPECT_EQ(station_.visitor_view().phase, VisitorPhase::attract);
  EXPECT_EQ(station_.visitor_view().visitor, 4u);          // four archived today before this run
  EXPECT_EQ(station_.exhibit_counters().ended_today, 4u);  // the metrics' visitors today
  const std::uint64_t base = station_.mesh().checksum();
  right_stroke(2.0f);
  right_stroke(-1.0f);
  EXPECT_EQ(notes(), std::vector<VisitorNote>{VisitorNote::began});
  const VisitorView v = station_.visitor_view();
  EXPECT_EQ(v.phase, VisitorPhase::sculpting);
  EXPECT_EQ(v.visitor, 5u);
  EXPECT_EQ(v.records, 2u);
  EXPECT_EQ(v.sculpture, 0x5B000001u);
  EXPECT_EQ(station_.exhibit_counters().ended_today, 4u);  // visitor 5 is not ended yet
  const std::uint64_t sculpted = station_.mesh().checksum();
  EXPECT_NE(sculpted, base);
  const std::vector<std::byte> journal(storage_.bytes().begin(), storage_.bytes().end());
  run_seconds(19.0);  // hands still: idle
  EXPECT_EQ(station_.visitor_view().phase, VisitorPhase::sculpting);
  run_seconds(1.5);
  EXPECT_EQ(notes(), std::vector<VisitorNote>{VisitorNote::ended});
  EXPECT_EQ(station_.visitor_view().phase, VisitorPhase::finished);
  EXPECT_TRUE(station_.visitor_view().flags & kVisitorFlagResetUndoable);
  EXPECT_EQ(station_.mesh().checksum(), sculpted);         // the grace: nothing reset yet
  EXPECT_EQ(station_.exhibit_counters().ended_today, 4u);  // counted once archived
  run_seconds(3.5);
  EXPECT_EQ(notes(), std::vector<VisitorNote>{VisitorNote::archived});
  // The note names the sculpture archived, not the new journal it rotated to.
  EXPECT_EQ(last_note_.sculpture, 0x5B000001u);
  EXPECT_EQ(last_note_.visitor, 5u);
  EXPECT_EQ(last_note_.records, 2u);
  EXPECT_EQ(last_note_.end, session::SculptureEnd::idle);
  ASSERT_EQ(archive_.entries.size(), 1u);
  const FakeArchive::Entry& a = archive_.entries[0];
  EXPECT_EQ(a.journal, journal);  // the whole journal, byte for byte
  EXPECT_EQ(a.checksum, sculpted);
  EXPECT_EQ(a.summary.sculpture, 0x5B000001u);
  EXPECT_EQ(a.summary.visitor, 5u);
  EXPECT_EQ(a.summary.records, 2u);
  EXPECT_EQ(a.summary.end, session::SculptureEnd::idle);
  // Rotated: a new journal (identity from the archive port) holding no record.
  EXPECT_EQ(station_.mesh().checksum(), base);
  EXPECT_EQ(station_.journal_records(), 0u);
  EXPECT_EQ(journal_id(), 0x5C000001u);
  EXPECT_EQ(station_.visitor_view().phase, VisitorPhase::attract);
  // The next visitor's strokes are records 0, 1 of the new journal.
  right_stroke(1.0f);
  EXPECT_EQ(station_.visitor_view().visitor, 6u);
  journal::JournalReader reader(storage_);
  ASSERT_TRUE(reader.open().ok());
  auto r = reader.next();
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->sequence, 0u);
  EXPECT_EQ(station_.exhibit_counters().archived, 1u);
  EXPECT_EQ(station_.exhibit_counters().ended_today, 5u);
}

TEST_F(ExhibitStation, TheChordEndsTheChordAgainUndoesTheEndInTheGrace) {
  start();
  right_stroke(2.0f);
  const std::uint64_t sculpted = station_.mesh().checksum();
  (void)notes();
  chord(true);
  run_seconds(0.5);
  EXPECT_EQ(station_.visitor_view().phase, VisitorPhase::sculpting);  // held only 0.5 s
  run_seconds(0.7);
  EXPECT_EQ(station_.visitor_view().phase, VisitorPhase::finished);
  chord(false);
  run_seconds(0.2);
  chord(true);
  run_seconds(1.2);
  chord(false);
  run_ticks(3);
  EXPECT_EQ(notes(), (std::vector<VisitorNote>{VisitorNote::ended, VisitorNote::undone}));
  EXPECT_EQ(station_.visitor_view().phase, VisitorPhase::sculpting);
  run_seconds(5.0);
  EXPECT_TRUE(archive_.entries.empty());
  EXPECT_EQ(station_.mesh().checksum(), sculpted);
  EXPECT_EQ(station_.exhibit_counters().undone, 1u);
}

TEST_F(ExhibitStation, DisplayCommandsEndUndoAndAreRefusedWithNothingToActOn) {
  start();
  EXPECT_EQ(station_.new_sculpture().code(), StatusCode::failed_precondition);  // attract
  EXPECT_EQ(station_.undo_new_sculpture().code(), StatusCode::failed_precondition);
  right_stroke(2.0f);
  EXPECT_TRUE(station_.new_sculpture().ok());
  EXPECT_TRUE(station_.undo_new_sculpture().ok());
  EXPECT_TRUE(station_.new_sculpture().ok());
  EXPECT_EQ(notes(), (std::vector<VisitorNote>{VisitorNote::refused, VisitorNote::refused,
                                               VisitorNote::began, VisitorNote::ended,
                                               VisitorNote::undone, VisitorNote::ended}));
  run_seconds(3.5);
  ASSERT_EQ(archive_.entries.size(), 1u);
  EXPECT_EQ(archive_.entries[0].summary.end, session::SculptureEnd::command);
}

TEST_F(ExhibitStation, AFullArchiveDiskChangesNothingIsReportedAndRetried) {
  start();
  right_stroke(2.0f);
  const std::uint64_t sculpted = station_.mesh().checksum();
  const std::vector<std::byte> journal(storage_.bytes().begin(), storage_.bytes().end());
  archive_.full = true;
  ASSERT_TRUE(station_.new_sculpture().ok());
  (void)notes();
  run_seconds(3.5);
  EXPECT_EQ(notes(), std::vector<VisitorNote>{VisitorNote::disk_full});
  VisitorView v = station_.visitor_view();
  EXPECT_EQ(v.phase, VisitorPhase::finished);
  EXPECT_EQ(v.flags & (kVisitorFlagArchiveFailed | kVisitorFlagDiskFull),
            kVisitorFlagArchiveFailed | kVisitorFlagDiskFull);
  EXPECT_EQ(station_.mesh().checksum(), sculpted);  // nothing reset, nothing cut
  EXPECT_TRUE(
      std::equal(journal.begin(), journal.end(), storage_.bytes().begin(), storage_.bytes().end()));
  // Sculpting goes on meanwhile (a grab goes back to sculpting, saved as ever).
  right_stroke(1.0f);
  EXPECT_EQ(station_.visitor_view().phase, VisitorPhase::sculpting);
  EXPECT_EQ(station_.journal_records(), 2u);
  ASSERT_TRUE(station_.new_sculpture().ok());
  archive_.full = false;
  run_seconds(3.5);
  ASSERT_EQ(archive_.entries.size(), 1u);
  EXPECT_EQ(archive_.entries[0].summary.records, 2u);
  EXPECT_EQ(station_.visitor_view().flags, 0);
  EXPECT_EQ(station_.exhibit_counters().disk_full, 1u);
  EXPECT_EQ(station_.exhibit_counters().ended_today, 5u);  // once, the refused try not
}

TEST_F(ExhibitStation, ARestartOnAJournalHoldingASculptureIsSculptingItsVisitorCounted) {
  start();
  right_stroke(2.0f);
  Station again(stream_, buttons_, clock_, storage_, *base_, work_->spans(), config_,
                StationFiles{nullptr, nullptr, nullptr, 1, &archive_, mesh_.get(), 4});
  // (the meshes swap roles: `again` replays onto base_, which is the grid too)
  ASSERT_TRUE(again.start().ok());
  EXPECT_EQ(again.visitor_view().phase, VisitorPhase::sculpting);
  EXPECT_EQ(again.visitor_view().visitor, 5u);
  EXPECT_EQ(again.journal_records(), 1u);
}

TEST_F(ExhibitStation, ARotationAllocatesNothing) {
  start();
  right_stroke(2.0f);
  right_stroke(1.0f);
  ASSERT_TRUE(station_.new_sculpture().ok());
  archive_.entries.reserve(4);
  test::AllocationCounter counter;
  run_seconds(3.5);
  right_stroke(1.0f);
  EXPECT_EQ(counter.count(), archive_.allocations);  // the fake's journal copy alone
  EXPECT_EQ(station_.exhibit_counters().archived, 1u);
}

// The display's side (link protocol 7): VisitorState on change and about once a second,
// the lifecycle's notices, new_sculpture / undo_new_sculpture commands acted on, and the
// base model sent after the rotation.
TEST_F(ExhibitStation, TheDisplayIsToldTheVisitorStateAndNoticesAndItsCommandsAct) {
  using namespace link;  // NOLINT
  test::MemoryWire wire;
  test::MemoryLinkEnd station_end(wire, true);
  test::MemoryLinkEnd bridge_end(wire, false);
  const std::size_t n = mesh_->vertex_capacity();
  std::vector<float> x(n), y(n), z(n);
  std::vector<std::uint32_t> idx(3 * mesh_->triangle_capacity());
  std::vector<std::byte> out(64 * kMaxFrameBytes);
  StationLink link(station_end, StationLinkStorage{x, y, z, idx, out}, StationLinkConfig{});
  start();
  ASSERT_TRUE(link.start(station_.sculpt()).ok());
  LinkDecoder decoder;
  const auto send = [&](const auto& m) {
    std::vector<std::byte> f(kMaxFrameBytes);
    const auto k = encode_frame(m, f);
    ASSERT_TRUE(k.ok());
    f.resize(*k);
    ASSERT_EQ(*bridge_end.send(f), f.size());
  };
  const auto receive = [&] {
    std::vector<LinkMessage> got;
    std::vector<std::byte> buf(1 << 16);
    for (;;) {
      const auto k = bridge_end.receive(buf);
      if (!k.ok() || *k == 0) break;
      for (std::size_t i = 0; i < *k; ++i) {
        if (const auto m = decoder.process(buf[i]); m.ok()) got.push_back(**m);
      }
    }
    return got;
  };
  const auto run = [&](double seconds) {
    for (int i = 0; i < static_cast<int>(seconds * 120); ++i) {
      run_ticks(1);
      link.poll(station_, clock_.now_us());
    }
  };
  const auto visitors = [](const std::vector<LinkMessage>& ms) {
    std::vector<VisitorState> v;
    for (const auto& m : ms) {
      if (const auto* s = std::get_if<VisitorState>(&m)) v.push_back(*s);
    }
    return v;
  };
  const auto notices = [](const std::vector<LinkMessage>& ms) {
    std::vector<NoticeCode> v;
    for (const auto& m : ms) {
      if (const auto* s = std::get_if<Notice>(&m)) v.push_back(s->code);
    }
    return v;
  };
  send(Hello{Role::bridge, 0, 0, 0, {}});
  run(0.5);
  std::vector<LinkMessage> got = receive();
  ASSERT_FALSE(visitors(got).empty());
  EXPECT_EQ(visitors(got).back().phase, link::VisitorPhase::attract);
  EXPECT_EQ(visitors(got).back().visitor, 4u);
  run(3.0);  // nothing changes: about once a second
  const std::size_t quiet = visitors(receive()).size();
  EXPECT_GE(quiet, 2u);
  EXPECT_LE(quiet, 4u);
  send(Command{CommandKind::new_sculpture, 0});  // nothing to end yet
  run(0.2);
  EXPECT_EQ(notices(receive()), std::vector<NoticeCode>{NoticeCode::nothing_to_act_on});
  right_stroke(2.0f);
  run(0.2);
  got = receive();
  EXPECT_EQ(visitors(got).back().phase, link::VisitorPhase::sculpting);
  EXPECT_EQ(visitors(got).back().strokes, 1u);
  EXPECT_EQ(visitors(got).back().visitor, 5u);
  send(Command{CommandKind::new_sculpture, 0});
  run(0.5);
  got = receive();
  EXPECT_EQ(visitors(got).back().phase, link::VisitorPhase::finished);
  EXPECT_EQ(visitors(got).back().flags, kVisitorResetUndoable);
  EXPECT_GT(visitors(got).back().grace_left_s, 2.0f);
  send(Command{CommandKind::undo_new_sculpture, 0});
  run(0.2);
  got = receive();
  EXPECT_EQ(notices(got), std::vector<NoticeCode>{NoticeCode::new_sculpture_undone});
  EXPECT_EQ(visitors(got).back().phase, link::VisitorPhase::sculpting);
  send(Command{CommandKind::new_sculpture, 0});
  run(4.0);
  got = receive();
  EXPECT_EQ(notices(got), std::vector<NoticeCode>{NoticeCode::sculpture_archived});
  EXPECT_EQ(visitors(got).back().phase, link::VisitorPhase::attract);
  EXPECT_EQ(visitors(got).back().sculpture, 0x5C000001u);
  EXPECT_EQ(visitors(got).back().strokes, 0u);
  bool base_sent = false;
  for (const auto& m : got) {
    if (const auto* e = std::get_if<MeshEnd>(&m)) base_sent |= e->checksum == base_->checksum();
  }
  EXPECT_TRUE(base_sent);  // the display shows the fresh model
}

class ExhibitOff : public ExhibitStation {
 protected:
  ExhibitOff() : ExhibitStation(false) {}
};

TEST_F(ExhibitOff, NothingEndsNothingIsArchivedNoEventIsAdded) {
  start();
  right_stroke(2.0f);
  run_seconds(60.0);
  EXPECT_TRUE(notes().empty());
  EXPECT_TRUE(archive_.entries.empty());
  EXPECT_EQ(station_.journal_records(), 1u);
  EXPECT_EQ(station_.new_sculpture().code(), StatusCode::failed_precondition);
}

// Notices (issue 25 "feedback for every refusal"), exhibit mode on or off: the paper's
// buttons but line 2 (hand 0) is undo and the chord hold line 1, press line 2 is redo,
// and a symmetry cycle of none and the x mirror (the paper's chord: hold line 4, press
// line 5).
StationConfig notice_config(bool exhibit) {
  StationConfig c = exhibit_config(exhibit);
  EXPECT_TRUE(c.sculpt.buttons.bind(2, 0, input::ButtonRole::undo).ok());
  const std::uint8_t redo_chord[] = {1, 2};
  EXPECT_TRUE(c.sculpt.buttons.bind_chord(redo_chord, 0, input::ButtonRole::redo).ok());
  EXPECT_TRUE(c.sculpt.symmetry_cycle.push(math::SymmetrySpec{}).ok());
  math::SymmetrySpec x;
  x.kind = math::SymmetryKind::mirrors;
  x.mirrors = math::kMirrorX;
  EXPECT_TRUE(c.sculpt.symmetry_cycle.push(x).ok());
  return c;
}

// The main display and a spectator on memory wires behind the fake listener: each
// says hello, the main one sends commands, both read what comes.
struct MemoryDisplay {
  explicit MemoryDisplay(const mesh::Mesh& mesh)
      : main_end(main_wire, false),
        spectator_end(spectator_wire, false),
        x(mesh.vertex_capacity()),
        y(mesh.vertex_capacity()),
        z(mesh.vertex_capacity()),
        idx(3 * mesh.triangle_capacity()),
        out(64 * link::kMaxFrameBytes),
        queues(16 * link::kMaxFrameBytes),
        link(listener, StationLinkStorage{x, y, z, idx, out}, StationLinkConfig{}, options()) {}
  StationLinkOptions options() {
    StationLinkOptions o;
    o.newcomers = &listener;
    o.spectators = &listener;
    o.max_spectators = 1;
    o.spectator_queues = queues;
    return o;
  }
  template <class M>
  static void send(test::MemoryLinkEnd& end, const M& m) {
    std::vector<std::byte> f(link::kMaxFrameBytes);
    const auto k = link::encode_frame(m, f);
    ASSERT_TRUE(k.ok());
    f.resize(*k);
    ASSERT_EQ(*end.send(f), f.size());
  }
  template <class M>
  void send(const M& m) {
    send(main_end, m);
  }
  // What one display received since the last call: its notices as (code, detail),
  // and how many visitor states.
  struct Received {
    std::vector<std::pair<link::NoticeCode, int>> notices;
    int visitor_states = 0;
  };
  static Received receive(test::MemoryLinkEnd& end, link::LinkDecoder& decoder) {
    Received got;
    std::vector<std::byte> buf(1 << 16);
    for (;;) {
      const auto k = end.receive(buf);
      if (!k.ok() || *k == 0) break;
      for (std::size_t i = 0; i < *k; ++i) {
        const auto m = decoder.process(buf[i]);
        if (!m.ok() || !*m) continue;
        if (const auto* n = std::get_if<link::Notice>(&**m)) {
          got.notices.emplace_back(n->code, n->detail);
        }
        if (std::holds_alternative<link::VisitorState>(**m)) ++got.visitor_states;
      }
    }
    return got;
  }
  // The main display's notices since the last call; the spectator's are kept.
  std::vector<std::pair<link::NoticeCode, int>> notices() {
    const Received s = receive(spectator_end, spectator_decoder);
    spectator.notices.insert(spectator.notices.end(), s.notices.begin(), s.notices.end());
    spectator.visitor_states += s.visitor_states;
    const Received m = receive(main_end, main_decoder);
    main_visitor_states += m.visitor_states;
    return m.notices;
  }

  test::FakeListener listener;
  test::MemoryWire main_wire;
  test::MemoryWire spectator_wire;
  test::MemoryLinkEnd main_end;
  test::MemoryLinkEnd spectator_end;
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> idx;
  std::vector<std::byte> out, queues;
  StationLink link;
  link::LinkDecoder main_decoder;
  link::LinkDecoder spectator_decoder;
  Received spectator;  // everything the spectator got
  int main_visitor_states = 0;
};

class NoticeStation : public ExhibitStation, public ::testing::WithParamInterface<bool> {
 protected:
  NoticeStation() : ExhibitStation(notice_config(GetParam())), display_(*mesh_) {}
  void run(double seconds) {
    for (int i = 0; i < static_cast<int>(seconds * 120); ++i) {
      run_ticks(1);
      display_.link.poll(station_, clock_.now_us());
    }
  }
  void click(std::uint8_t line) {
    buttons_.press(line, true, clock_.now_us());
    run(0.05);
    buttons_.press(line, false, clock_.now_us());
    run(0.2);
  }
  void chord_click(std::uint8_t held, std::uint8_t trigger) {
    buttons_.press(held, true, clock_.now_us());
    run(0.05);
    click(trigger);
    buttons_.press(held, false, clock_.now_us());
    run(0.2);
  }
  void undo_button() { click(2); }
  void redo_button() { chord_click(1, 2); }
  MemoryDisplay display_;
};

using N = link::NoticeCode;
using R = input::Reason;
using Notices = std::vector<std::pair<link::NoticeCode, int>>;
int d(R r) { return static_cast<int>(r); }

// Each refusal and each change of the next stroke's group: exactly one notice with its
// code (the buttons' path and the display's commands alike); strokes, undo and redo
// that act, and a quiet run: none.
TEST_P(NoticeStation, EachRefusalAndSymmetryChangeIsOneNoticeAndAQuietRunNone) {
  using namespace link;  // NOLINT
  start();
  ASSERT_TRUE(display_.link.start(station_.sculpt()).ok());
  display_.listener.connect(display_.main_wire);
  display_.send(Hello{Role::bridge, 0, 0, 0, {}});
  run(0.5);
  ASSERT_TRUE(display_.link.admitted());
  display_.listener.connect(display_.spectator_wire);
  MemoryDisplay::send(display_.spectator_end, Hello{Role::bridge, kHelloSpectator, 0, 0, {}});
  run(0.5);
  ASSERT_EQ(display_.link.counters().spectators_now, 1u);
  run(5.0);  // a stroke-free run
  EXPECT_EQ(display_.notices(), Notices{});

  undo_button();  // nothing to undo
  EXPECT_EQ(display_.notices(), (Notices{{N::undo_refused, d(R::nothing_to_undo)}}));
  display_.send(Command{CommandKind::undo, 0});
  run(0.2);
  EXPECT_EQ(display_.notices(), (Notices{{N::undo_refused, d(R::nothing_to_undo)}}));
  redo_button();
  EXPECT_EQ(display_.notices(), (Notices{{N::redo_refused, d(R::nothing_to_redo)}}));
  display_.send(Command{CommandKind::redo, 0});
  run(0.2);
  EXPECT_EQ(display_.notices(), (Notices{{N::redo_refused, d(R::nothing_to_redo)}}));

  // The chord (hold line 4, press line 5) and the display's key S.
  chord_click(4, 5);
  EXPECT_EQ(display_.notices(), (Notices{{N::symmetry_changed, int(math::SymmetryKind::mirrors)}}));
  display_.send(Command{CommandKind::cycle_symmetry, 0});
  run(0.2);
  EXPECT_EQ(display_.notices(), (Notices{{N::symmetry_changed, int(math::SymmetryKind::none)}}));

  // A stroke, its undo and redo act: no notice.
  right_stroke(2.0f);
  display_.send(Command{CommandKind::undo, 0});
  run(0.2);
  display_.send(Command{CommandKind::redo, 0});
  run(0.2);
  undo_button();
  redo_button();
  EXPECT_EQ(display_.notices(), Notices{});
  EXPECT_EQ(station_.journal_records(), 5u);  // the stroke, two undos, two redos

  // While a stroke is open: undo, redo and the next method are refused (busy).
  right_in_ = {10.0f, 0.0f, 5.0f};
  buttons_.press(3, true, clock_.now_us());
  run(0.1);
  display_.send(Command{CommandKind::undo, 0});
  run(0.1);
  display_.send(Command{CommandKind::redo, 0});
  run(0.1);
  display_.send(Command{CommandKind::next_method, 0});
  run(0.1);
  buttons_.press(3, false, clock_.now_us());
  run(0.2);
  EXPECT_EQ(display_.notices(), (Notices{{N::undo_refused, d(R::busy)},
                                         {N::redo_refused, d(R::busy)},
                                         {N::nothing_to_act_on, d(R::busy)}}));
  run(3.0);
  const Notices all{{N::undo_refused, d(R::nothing_to_undo)},
                    {N::undo_refused, d(R::nothing_to_undo)},
                    {N::redo_refused, d(R::nothing_to_redo)},
                    {N::redo_refused, d(R::nothing_to_redo)},
                    {N::symmetry_changed, int(math::SymmetryKind::mirrors)},
                    {N::symmetry_changed, int(math::SymmetryKind::none)},
                    {N::undo_refused, d(R::busy)},
                    {N::redo_refused, d(R::busy)},
                    {N::nothing_to_act_on, d(R::busy)}};
  EXPECT_EQ(display_.notices(), Notices{});
  // The spectator saw the same notices, and the visitor state as the main display did.
  EXPECT_EQ(display_.spectator.notices, all);
  const bool exhibit = GetParam();
  EXPECT_EQ(display_.main_visitor_states > 0, exhibit);
  EXPECT_EQ(display_.spectator.visitor_states > 0, exhibit);
}

INSTANTIATE_TEST_SUITE_P(ExhibitOnAndOff, NoticeStation, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& i) {
                           return i.param ? std::string("exhibit_on") : std::string("exhibit_off");
                         });

// More notices in one poll than the board holds: the newest kCapacity reach the
// display, in order, each once.
TEST(NoticeBoard, KeepsTheNewestNumberedAndMapsEventsToCodes) {
  NoticeBoard board;
  EXPECT_EQ(board.posted(), 0u);
  EXPECT_EQ(board.oldest(), 1u);
  for (std::uint8_t i = 1; i <= 10; ++i) board.post({link::NoticeCode::undo_refused, i});
  EXPECT_EQ(board.posted(), 10u);
  EXPECT_EQ(board.oldest(), 3u);
  for (std::uint32_t k = 3; k <= 10; ++k) EXPECT_EQ(board.at(k).detail, k);
  link::Notice n;
  using session::SessionEventKind;
  EXPECT_FALSE(notice_for(session::make_event(SessionEventKind::grab_begin, 0), n));
  EXPECT_FALSE(notice_for(
      session::make_event(SessionEventKind::undone, 0, session::payload::RecordRef{1}), n));
  ASSERT_TRUE(notice_for(
      session::make_event(SessionEventKind::refused, 1, session::payload::Reasoned{R::no_tracking}),
      n));
  EXPECT_EQ(n.code, link::NoticeCode::nothing_to_act_on);
  EXPECT_EQ(n.detail, d(R::no_tracking));
  session::payload::Visitor v;
  v.note = VisitorNote::archived;
  v.visitor = 300;
  ASSERT_TRUE(notice_for(session::make_event(SessionEventKind::visitor, 0, v), n));
  EXPECT_EQ(n.code, link::NoticeCode::sculpture_archived);
  EXPECT_EQ(n.detail, 255);
  v.note = VisitorNote::began;
  EXPECT_FALSE(notice_for(session::make_event(SessionEventKind::visitor, 0, v), n));
}

}  // namespace
}  // namespace twister::station
