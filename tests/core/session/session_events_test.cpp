#include "twister/session/session_events.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace twister::session {
namespace {

TEST(SessionEvents, KeepsTheOrderAndCountsWhatDoesNotFit) {
  SessionEvents e;
  for (std::uint32_t i = 0; i < kMaxEventsPerStep + 3; ++i) {
    e.push({SessionEventKind::committed, 0, input::Reason::none, ok_status(), i});
  }
  ASSERT_EQ(e.items().size(), kMaxEventsPerStep);
  for (std::uint32_t i = 0; i < kMaxEventsPerStep; ++i) EXPECT_EQ(e.items()[i].sequence, i);
  EXPECT_EQ(e.dropped(), 3u);
}

TEST(SessionEvents, EveryKindHasItsOwnName) {
  constexpr int kKinds = static_cast<int>(SessionEventKind::history_overflow) + 1;
  for (int a = 0; a < kKinds; ++a) {
    const char* name = session_event_kind_name(static_cast<SessionEventKind>(a));
    EXPECT_STRNE(name, "unknown");
    for (int b = 0; b < a; ++b) {
      EXPECT_STRNE(name, session_event_kind_name(static_cast<SessionEventKind>(b)));
    }
  }
}

}  // namespace
}  // namespace twister::session
