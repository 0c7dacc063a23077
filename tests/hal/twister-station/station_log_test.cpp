// twister-station's log lines (issue "a session"): every SessionEvent kind has a line
// at its level; the sculptor's actions besides strokes (radius, clutch, turn limit,
// undo/redo, method, refused commands) read as docs/hardware.md lists them.
// Label interaction.
#include "station_log.hpp"

#include <gtest/gtest.h>

#include <array>
#include <numbers>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "twister/hal/logger.hpp"
#include "twister/input/interaction_machine.hpp"
#include "twister/session/session_command.hpp"

namespace twister::station_app {
namespace {

using ports::LogLevel;
using session::SessionEvent;
using session::SessionEventKind;

struct Line {
  LogLevel level;
  std::string component;
  std::string text;
};

class RecordingLog final : public ports::LogSink {
 public:
  std::vector<Line> lines;

 private:
  bool do_enabled(LogLevel) const override { return true; }
  void do_write(LogLevel level, const char* component, const char* format,
                std::span<const ports::LogArg> args) override {
    std::array<char, 512> text{};
    hal::format_log_message(text, format, args);
    lines.push_back({level, component, text.data()});
  }
};

// A payload of the kind's type (default values).
session::EventPayload sample_payload(SessionEventKind kind) {
  session::EventPayload p;
  const std::size_t want = session::payload_index(kind);
  // Default-construct the alternative `want` (the variant's types in order).
  [&]<std::size_t... I>(std::index_sequence<I...>) { ((I == want ? (p.emplace<I>(), 0) : 0), ...); }
  (std::make_index_sequence<std::variant_size_v<session::EventPayload>>{});
  return p;
}

Line line_of(const SessionEvent& e) {
  RecordingLog log;
  log_station_event(e, log);
  EXPECT_EQ(log.lines.size(), 1u) << session::session_event_kind_name(e.kind);
  return log.lines.empty() ? Line{} : log.lines[0];
}

TEST(StationLog, EveryKindHasOneLineAtItsLevel) {
  for (std::size_t k = 0; k < session::kSessionEventKindCount; ++k) {
    const auto kind = static_cast<SessionEventKind>(k);
    const SessionEvent e = session::make_event(kind, 0, sample_payload(kind));
    const Line l = line_of(e);
    EXPECT_EQ(l.level, station_event_level(e)) << k;
    EXPECT_FALSE(l.text.empty()) << k;
    EXPECT_EQ(l.text.find('?'), std::string::npos) << l.text;  // every argument given
  }
}

TEST(StationLog, TheSculptorsActions) {
  SessionEvent e =
      session::make_event(SessionEventKind::radius_set, 0, session::payload::Radius{0.5});
  Line l = line_of(e);
  EXPECT_EQ(l.level, LogLevel::notice);
  EXPECT_EQ(l.component, "sculpt");
  EXPECT_EQ(l.text, "radius 0.500 m");

  e = session::make_event(SessionEventKind::turn_limit_reached, 1,
                          session::payload::TurnLimit{330.0 * std::numbers::pi / 180.0});
  l = line_of(e);
  EXPECT_EQ(l.level, LogLevel::notice);
  EXPECT_EQ(l.text,
            "hand 1 turned past the 330-degree limit; the warp holds until the hand turns back");

  e = session::make_event(SessionEventKind::disengaged, 1, session::payload::RecordRef{4});
  l = line_of(e);
  EXPECT_EQ(l.level, LogLevel::info);
  EXPECT_EQ(l.text,
            "hand 1 on the clutch (freeze held): committed as journal record 4; the hand moves "
            "freely");

  e = session::make_event(SessionEventKind::undone, 0, session::payload::RecordRef{7});
  l = line_of(e);
  EXPECT_EQ(l.level, LogLevel::notice);
  EXPECT_EQ(l.component, "history");
  EXPECT_EQ(l.text, "undo (journal record 7)");

  e = session::make_event(SessionEventKind::method_changed, 0,
                          session::payload::Method{math::WarpMethod::scodef});
  EXPECT_EQ(line_of(e).text, "warp method scodef for the next strokes");

  e = session::make_event(SessionEventKind::command_refused, 0,
                          session::payload::CommandRefusal{session::SessionCommandKind::redo,
                                                           input::Reason::nothing_to_redo});
  l = line_of(e);
  EXPECT_EQ(l.level, LogLevel::notice);
  EXPECT_EQ(l.text, "redo refused (nothing_to_redo)");
}

}  // namespace
}  // namespace twister::station_app
