// Append failures during a live session (issue 11, item 2): the disk fills at every
// byte of a scripted session (freeze chains, two hands, an object move, undo), and
// fsync or truncate fail. Whatever happens: a commit reported saved is in the journal
// with its sequence, a commit not saved left the model unchanged (the model always
// equals a replay of the journal, bit for bit), sequences have no gaps, chain steps
// never skip, and the journal always replays (a restart never refuses it).
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <set>
#include <vector>

#include "session_harness.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::session {
namespace {

using namespace test_support;
constexpr double kPi = std::numbers::pi;

// What the session reported: sequences of saved commits, count of not-saved ones.
struct Reported {
  std::set<std::uint32_t> saved;
  std::size_t not_saved = 0;
};

struct Sculptor {
  Station& s;
  Reported& seen;
  void tick() {
    const SessionEvents events = s.tick();  // items() views it: keep it alive
    for (const SessionEvent& e : events.items()) {
      if (e.kind == SessionEventKind::committed || e.kind == SessionEventKind::move_committed) {
        EXPECT_TRUE(e.status.ok());
        seen.saved.insert(e.kind == SessionEventKind::move_committed ? e.record().sequence
                                                                     : e.stroke_end().sequence);
      }
      if (e.kind == SessionEventKind::not_saved) ++seen.not_saved;
    }
  }
  void freeze_chain(glm::dvec3 at, int steps) {
    s.hand(1, z_turn(at, 0));
    s.button(kGrab1, true);
    tick();
    for (int step = 1; step <= steps; ++step) {
      s.hand(1, z_turn(at + glm::dvec3(0, 0, 0.04 * step), 2 * kPi / 3 * step));
      tick();
      s.button(kFreeze1, true);
      tick();
      s.button(kFreeze1, false);
      tick();
    }
    s.button(kGrab1, false);
    tick();
  }
  void two_hands() {
    s.hand(0, math::identity_frame({-0.4, 0.1, 0}));
    s.hand(1, math::identity_frame({0.4, 0.1, 0}));
    s.button(kGrab0, true);
    s.button(kGrab1, true);
    tick();
    s.hand(0, z_turn({-0.4, 0.1, 0.2}, 0.5));
    s.hand(1, z_turn({0.4, 0.1, -0.2}, -0.5));
    tick();
    s.button(kGrab0, false);
    tick();
    s.hand(1, z_turn({0.5, 0.2, -0.1}, -0.2));
    tick();
    s.button(kFreeze1, true);
    tick();
    s.button(kFreeze1, false);
    s.button(kGrab1, false);
    tick();
  }
  void move_object() {
    s.hand(0, math::identity_frame({1, 1, 1}));
    s.button(kMove0, true);
    tick();
    s.hand(0, z_turn({1.2, 0.9, 1.1}, 0.3));
    tick();
    s.button(kMove0, false);
    tick();
  }
  void undo() {
    const Status st = s.session->undo();
    if (st.ok()) seen.saved.insert(s.session->next_sequence() - 1);
    if (st.code() == StatusCode::io_error) ++seen.not_saved;
  }
  void script() {
    freeze_chain({0.3, -0.2, 0}, 4);
    two_hands();
    move_object();
    undo();
    freeze_chain({-0.3, 0.3, 0}, 3);
  }
};

struct Replayed {
  std::uint64_t checksum = 0;
  math::Frame object{};
  std::vector<std::uint32_t> sequences;
  Status status{};
  journal::TailProblem problem = journal::TailProblem::none;
};

Replayed replay_journal(TestStorage& storage) {
  auto fresh = std::make_unique<Station>(33, test_config(), false);
  journal::JournalReader reader(storage);
  Replayed out;
  out.status = reader.open();
  if (!out.status.ok()) return out;
  for (;;) {
    auto r = reader.next();
    if (!r.ok()) break;
    out.sequences.push_back(r->sequence);
    out.status = fresh->session->apply_record(*r);
    if (!out.status.ok()) return out;
  }
  out.problem = reader.problem();
  out.checksum = fresh->mesh.checksum();
  out.object = fresh->session->object_pose();
  return out;
}

// The journal is exactly what was reported saved, and rebuilds the live model.
void expect_journal_matches(Station& s, const Reported& seen) {
  const Replayed r = replay_journal(s.storage);
  ASSERT_TRUE(r.status.ok()) << r.status.name();
  EXPECT_EQ(r.problem, journal::TailProblem::none);
  const std::vector<std::uint32_t> reported(seen.saved.begin(), seen.saved.end());
  EXPECT_EQ(r.sequences, reported);
  for (std::size_t i = 0; i < r.sequences.size(); ++i) EXPECT_EQ(r.sequences[i], i);
  EXPECT_EQ(r.checksum, s.mesh.checksum());
  EXPECT_EQ(r.object.origin, s.session->object_pose().origin);
  EXPECT_EQ(s.session->next_sequence(), r.sequences.size());
}

std::size_t full_session_bytes() {
  auto s = std::make_unique<Station>();
  Reported seen;
  Sculptor{*s, seen}.script();
  EXPECT_EQ(seen.not_saved, 0u);
  return s->storage.bytes().size();
}

TEST(JournalDiskFull, AtEveryByteOfASessionNothingReportedSavedIsLostAndRestartWorks) {
  const std::size_t total = full_session_bytes();
  ASSERT_GT(total, 1000u);
  std::size_t runs_with_losses = 0;
  for (std::size_t limit = journal::kMaxFileHeaderBytes; limit <= total; ++limit) {
    SCOPED_TRACE(limit);
    auto s = std::make_unique<Station>();
    s->storage.fill_disk_at(limit);
    Reported seen;
    Sculptor sculptor{*s, seen};
    sculptor.script();
    if (limit < total) {
      EXPECT_GT(seen.not_saved, 0u);
      ++runs_with_losses;
    }
    expect_journal_matches(*s, seen);
    // Space is freed: the same station saves again, after its last good record.
    s->storage.free_disk();
    sculptor.freeze_chain({0.1, 0.1, 0}, 2);
    sculptor.undo();
    expect_journal_matches(*s, seen);
    if (HasFailure()) break;
  }
  EXPECT_GT(runs_with_losses, 1000u);
}

TEST(JournalDiskFull, FailedSyncsAndTruncatesNeverBreakTheJournal) {
  for (int fail_at = 0; fail_at < 18; ++fail_at) {
    SCOPED_TRACE(fail_at);
    auto s = std::make_unique<Station>();
    Reported seen;
    Sculptor sculptor{*s, seen};
    // A failing fsync at the fail_at-th record, with a failing truncate behind it:
    // the writer is broken until the storage truncates again.
    for (int i = 0; i < fail_at; ++i) sculptor.freeze_chain({0.2, 0, 0}, 1);
    s->storage.fail_next_sync();
    s->storage.fail_truncates(true);
    sculptor.freeze_chain({-0.2, 0, 0}, 2);
    EXPECT_GT(seen.not_saved, 0u);
    s->storage.fail_truncates(false);
    sculptor.freeze_chain({0, 0.2, 0}, 2);
    expect_journal_matches(*s, seen);
  }
}

}  // namespace
}  // namespace twister::session
