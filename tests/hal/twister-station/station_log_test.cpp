// twister-station's log lines (issue "a session"): every StationEvent kind has a line
// at its level; the sculptor's actions besides strokes (radius, clutch, turn limit,
// undo/redo, method, refused commands) read as docs/hardware.md lists them.
// Label interaction.
#include "station_log.hpp"

#include <gtest/gtest.h>

#include <array>
#include <numbers>
#include <string>
#include <vector>

#include "twister/hal/logger.hpp"
#include "twister/input/interaction_machine.hpp"
#include "twister/session/session_command.hpp"

namespace twister::station_app {
namespace {

using ports::LogLevel;
using station::StationEvent;
using station::StationEventKind;

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

Line line_of(const StationEvent& e) {
  RecordingLog log;
  log_station_event(e, log);
  EXPECT_EQ(log.lines.size(), 1u) << station::station_event_kind_name(e.kind);
  return log.lines.empty() ? Line{} : log.lines[0];
}

TEST(StationLog, EveryKindHasOneLineAtItsLevel) {
  for (int k = 0; k <= static_cast<int>(StationEventKind::refinement_stopped); ++k) {
    StationEvent e;
    e.kind = static_cast<StationEventKind>(k);
    const Line l = line_of(e);
    EXPECT_EQ(l.level, station_event_level(e)) << k;
    EXPECT_FALSE(l.text.empty()) << k;
    EXPECT_EQ(l.text.find('?'), std::string::npos) << l.text;  // every argument given
  }
}

TEST(StationLog, TheSculptorsActions) {
  StationEvent e;
  e.kind = StationEventKind::radius_set;
  e.real = 0.5;
  Line l = line_of(e);
  EXPECT_EQ(l.level, LogLevel::notice);
  EXPECT_EQ(l.component, "sculpt");
  EXPECT_EQ(l.text, "radius 0.500 m");

  e = {};
  e.kind = StationEventKind::turn_limit_reached;
  e.hand = 1;
  e.real = 330.0 * std::numbers::pi / 180.0;
  l = line_of(e);
  EXPECT_EQ(l.level, LogLevel::notice);
  EXPECT_EQ(l.text,
            "hand 1 turned past the 330-degree limit; the warp holds until the hand turns back");

  e = {};
  e.kind = StationEventKind::hand_disengaged;
  e.hand = 1;
  e.sequence = 4;
  l = line_of(e);
  EXPECT_EQ(l.level, LogLevel::info);
  EXPECT_EQ(l.text,
            "hand 1 on the clutch (freeze held): committed as journal record 4; the hand moves "
            "freely");

  e = {};
  e.kind = StationEventKind::undone;
  e.sequence = 7;
  l = line_of(e);
  EXPECT_EQ(l.level, LogLevel::notice);
  EXPECT_EQ(l.component, "history");
  EXPECT_EQ(l.text, "undo (journal record 7)");

  e = {};
  e.kind = StationEventKind::method_changed;
  e.value = 2;
  EXPECT_EQ(line_of(e).text, "warp method scodef for the next strokes");

  e = {};
  e.kind = StationEventKind::command_refused;
  e.value = static_cast<std::uint64_t>(session::SessionCommandKind::redo);
  e.detail = static_cast<std::uint8_t>(input::Reason::nothing_to_redo);
  l = line_of(e);
  EXPECT_EQ(l.level, LogLevel::notice);
  EXPECT_EQ(l.text, "redo refused (nothing_to_redo)");
}

}  // namespace
}  // namespace twister::station_app
