#include "twister/session/session_events.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace twister::session {
namespace {

TEST(SessionEvents, KeepsTheOrderAndCountsWhatDoesNotFit) {
  SessionEvents e;
  for (std::uint32_t i = 0; i < kMaxEventsPerStep + 3; ++i) {
    e.push(make_event(SessionEventKind::committed, 0, payload::StrokeEnd{input::Reason::none, i}));
  }
  ASSERT_EQ(e.items().size(), kMaxEventsPerStep);
  for (std::uint32_t i = 0; i < kMaxEventsPerStep; ++i) {
    EXPECT_EQ(e.items()[i].stroke_end().sequence, i);
  }
  EXPECT_EQ(e.dropped(), 3u);
}

TEST(SessionEvents, EveryKindHasItsOwnName) {
  for (std::size_t a = 0; a < kSessionEventKindCount; ++a) {
    const char* name = session_event_kind_name(static_cast<SessionEventKind>(a));
    EXPECT_STRNE(name, "unknown");
    for (std::size_t b = 0; b < a; ++b) {
      EXPECT_STRNE(name, session_event_kind_name(static_cast<SessionEventKind>(b)));
    }
  }
}

}  // namespace
}  // namespace twister::session
