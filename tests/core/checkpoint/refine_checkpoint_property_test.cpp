// Checkpoints with refinement on, as a property (format version 2): random stroke
// sequences (one or two hands, turns up to 170 degrees about any axis, clutch steps)
// with undo and redo on a coarse box refined at commit; a checkpoint taken at a random
// point plus a replay of the records after it builds exactly what a replay of the
// whole journal builds (checksum, every history entry and change, pose, sequence), also
// when the capacity ran out; undoing everything afterwards goes step for step the same.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <memory>

#include "checkpoint_harness.hpp"
#include "core/session/refine_harness.hpp"
#include "core/session/refine_random.hpp"

namespace twister::checkpoint {
namespace {

using namespace test_support;

void random_steps(RefineStation& s, int strokes) {
  for (int i = 0; i < strokes; ++i) {
    random_stroke(s);
    const int history = *rc::gen::inRange(0, 6);
    if (history == 0) (void)s.session->undo();
    if (history == 1 && s.session->undo().ok()) RC_ASSERT(s.session->redo().ok());
    if (history == 2) {
      (void)s.session->undo();
      (void)s.session->undo();
    }
  }
}

// Applies the journal of `from` after `offset` to `to`.
void replay_after(RefineStation& from, std::uint64_t offset, RefineStation& to) {
  journal::JournalReader reader(from.storage);
  RC_ASSERT(reader.open().ok());
  if (offset > 0) RC_ASSERT(reader.seek(offset).ok());
  RC_ASSERT(to.session->replay(reader).ok());
}

RC_GTEST_PROP(RefineCheckpointProperty, RestoreThenTheRestEqualsAFullReplay, ()) {
  const double threshold = *rc::gen::element(0.004, 0.01, 0.03);
  const auto spare = static_cast<std::size_t>(*rc::gen::element(200, 2'000, 12'000));
  auto live = std::make_unique<RefineStation>(3, spare, refine_config(threshold));
  const std::uint64_t base = live->mesh().checksum();
  random_steps(*live, *rc::gen::inRange(0, 6));
  const Bytes checkpoint = checkpoint_of(*live, base);
  const std::uint64_t offset = live->writer.size();
  random_steps(*live, *rc::gen::inRange(0, 4));

  // The replaying sessions' own settings do not matter: the journal has the thresholds.
  auto full = std::make_unique<RefineStation>(3, spare, refine_config(0.05, false), false);
  replay_after(*live, 0, *full);
  auto restored = std::make_unique<RefineStation>(3, spare, refine_config(0.05, false), false);
  RC_ASSERT(restore_bytes(checkpoint, *restored).ok());
  RC_TAG(topology_count(restored->session->history()) > 0 ? "checkpoint with topology"
                                                          : "checkpoint without topology");
  RC_TAG(restored->session->history().redo_depth() > 0 ? "redo tail" : "no redo tail");
  replay_after(*live, offset, *restored);
  RC_ASSERT(full->mesh().checksum() == live->mesh().checksum());
  RC_ASSERT(restored->mesh().checksum() == full->mesh().checksum());
  RC_ASSERT(same_session(*restored, *full));
  RC_ASSERT(same_history(live->session->history(), restored->session->history()));
  for (int i = 0; i < 40; ++i) {
    const Status a = full->session->undo();
    const Status b = restored->session->undo();
    RC_ASSERT(a.code() == b.code());
    RC_ASSERT(restored->mesh().checksum() == full->mesh().checksum());
    if (!a.ok()) break;
  }
}

}  // namespace
}  // namespace twister::checkpoint
