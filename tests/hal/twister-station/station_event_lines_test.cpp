// Every kind of the station's event vocabulary formats to one log line that names the
// fields of its payload (issue 20): distinctive values go in, the line must carry them.
// Label architecture.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "station_log.hpp"
#include "twister/hal/logger.hpp"
#include "twister/session/session_events.hpp"

namespace twister::station_app {
namespace {

using session::make_event;
using session::SessionEvent;
using K = session::SessionEventKind;
namespace payload = session::payload;

class OneLine final : public ports::LogSink {
 public:
  std::vector<std::string> lines;

 private:
  bool do_enabled(ports::LogLevel) const override { return true; }
  void do_write(ports::LogLevel, const char*, const char* format,
                std::span<const ports::LogArg> args) override {
    std::array<char, 512> text{};
    hal::format_log_message(text, format, args);
    lines.emplace_back(text.data());
  }
};

// One event of each kind with distinctive fields, and what its line must contain.
struct Case {
  SessionEvent event;
  std::vector<std::string> names;
};

std::vector<Case> cases() {
  using R = input::Reason;
  return {
      {make_event(K::grab_begin, 1), {"hand 1"}},
      {make_event(K::committed, 1, payload::StrokeEnd{R::released, 4242}), {"hand 1", "4242"}},
      {make_event(K::cancelled, 1, payload::StrokeEnd{R::tracking_timeout}),
       {"hand 1", "tracking lost"}},
      {make_event(K::cancelled, 1, payload::StrokeEnd{R::stopped}), {"station stopping"}},
      {make_event(K::tracking_lost, 1), {"hand 1"}},
      {make_event(K::tracking_resumed, 1), {"hand 1"}},
      {make_event(K::refused, 1, payload::Reasoned{R::same_point}), {"hand 1", "same_point"}},
      {make_event(K::radius_changed, 0, payload::Radius{0.123}), {"0.123"}},
      {make_event(K::move_begin, 1), {"hand 1"}},
      {make_event(K::move_committed, 1, payload::RecordRef{4242}), {"hand 1", "4242"}},
      {make_event(K::move_cancelled, 1, payload::Reasoned{R::tracking_timeout}),
       {"hand 1", "tracking lost"}},
      {make_event(K::undone, 0, payload::RecordRef{4242}), {"undo", "4242"}},
      {make_event(K::redone, 0, payload::RecordRef{4242}), {"redo", "4242"}},
      {make_event(K::not_saved, 1, payload::StrokeEnd{R::released, 4242}, StatusCode::io_error),
       {"hand 1", "io_error"}},
      {make_event(K::history_overflow, 0, payload::RecordRef{4242}, StatusCode::resource_exhausted),
       {"4242"}},
      {make_event(K::radius_set, 0, payload::Radius{0.123}), {"0.123"}},
      {make_event(K::disengaged, 1, payload::RecordRef{4242}), {"hand 1", "4242"}},
      {make_event(K::engaged, 1), {"hand 1"}},
      {make_event(K::turn_limit_reached, 1, payload::TurnLimit{1.0}), {"hand 1", "57-degree"}},
      {make_event(K::turn_limit_left, 1, payload::TurnLimit{1.0}), {"hand 1"}},
      {make_event(K::method_changed, 0, payload::Method{math::WarpMethod::rottran}), {"rottran"}},
      {make_event(K::symmetry_changed, 1,
                  payload::Symmetry{{math::SymmetryKind::rotation, 0, 2, 6}}),
       {"symmetry rot6 z"}},
      {make_event(K::command_refused, 0,
                  payload::CommandRefusal{session::SessionCommandKind::undo, R::nothing_to_undo}),
       {"undo", "nothing_to_undo"}},
      {make_event(K::refined, 0, payload::Refinement{4242, 777}), {"4242", "777"}},
      {make_event(K::refine_stopped, 0,
                  payload::RefinementStop{4242, mesh::RefineStop::triangle_capacity},
                  StatusCode::resource_exhausted),
       {"4242", "triangle capacity"}},
      {make_event(K::journal_recovered, 0, payload::JournalRecovered{4242, 777}), {"4242", "777"}},
      {make_event(K::tracker_streaming, 0, payload::TrackerStreaming{3}), {"#3"}},
      {make_event(K::tracker_lost, 0), {"lost"}},
      {make_event(K::buttons_lost, 0, {}, StatusCode::io_error), {"io_error", "missing"}},
      {make_event(K::buttons_found, 0), {"found"}},
      {make_event(K::checkpoint_written, 0, payload::CheckpointWritten{4242, 777}),
       {"4242", "777"}},
      {make_event(K::checkpoint_failed, 0, {}, StatusCode::io_error), {"io_error"}},
      {make_event(K::visitor, 0,
                  payload::Visitor{session::VisitorNote::archive_failed,
                                   session::SculptureEnd::idle, 12, 0x2a, 77},
                  StatusCode::io_error),
       {"visitor 12", "0000002a", "77 journal records", "idle", "io_error"}},
  };
}

TEST(StationEventLines, EveryKindFormatsOneLineNamingItsFields) {
  std::array<bool, session::kSessionEventKindCount> seen{};
  for (const Case& c : cases()) {
    seen[static_cast<std::size_t>(c.event.kind)] = true;
    OneLine log;
    log_station_event(c.event, log);
    const char* kind = session::session_event_kind_name(c.event.kind);
    ASSERT_EQ(log.lines.size(), 1u) << kind;
    for (const std::string& name : c.names) {
      EXPECT_NE(log.lines[0].find(name), std::string::npos) << kind << ": " << log.lines[0];
    }
  }
  for (std::size_t k = 0; k < seen.size(); ++k) {
    EXPECT_TRUE(seen[k]) << "no case for " << session::session_event_kind_name(static_cast<K>(k));
  }
}

}  // namespace
}  // namespace twister::station_app
