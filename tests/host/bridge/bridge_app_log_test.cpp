// BridgeApp's messages through the LogSink it is given: level and component of each
// (connect notice, link loss warning, full mesh and commit notices on "replica",
// a rejected change set a warning), and nothing formatted above the threshold.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "bridge_link_rig.hpp"
#include "twister/hal/logger.hpp"

namespace twister::bridge {
namespace {

using ports::LogLevel;

struct Line {
  LogLevel level;
  std::string component;
  std::string text;
};

// Keeps every line at or above `threshold` (formatted as the program's logger does).
class RecordingLog final : public ports::LogSink {
 public:
  explicit RecordingLog(LogLevel threshold) : threshold_(threshold) {}
  std::vector<Line> lines;

  // Lines at `level` from `component` containing `text`.
  std::size_t count(LogLevel level, const std::string& component, const std::string& text) const {
    std::size_t n = 0;
    for (const Line& l : lines) {
      n += l.level == level && l.component == component && l.text.find(text) != std::string::npos;
    }
    return n;
  }

 private:
  bool do_enabled(LogLevel level) const override {
    return static_cast<int>(level) <= static_cast<int>(threshold_);
  }
  void do_write(LogLevel level, const char* component, const char* format,
                std::span<const ports::LogArg> args) override {
    std::array<char, 512> text{};
    hal::format_log_message(text, format, args);
    lines.push_back({level, component, text.data()});
  }
  LogLevel threshold_;
};

TEST(BridgeAppLog, LinkAndReplicaEventsCarryTheirLevelAndComponent) {
  RecordingLog log(LogLevel::debug);
  test_support::BridgeLinkRig r(log);
  r.run();
  EXPECT_EQ(log.count(LogLevel::notice, "link", "connected (holding mesh version 0)"), 1u);
  EXPECT_EQ(log.count(LogLevel::notice, "replica", "mesh version 1: "), 1u);
  r.stroke(0.1);
  r.run();
  EXPECT_EQ(log.count(LogLevel::notice, "replica", "commit -> mesh version 2, checksum "), 1u);
  r.wire.cut();
  r.run(3);
  EXPECT_EQ(log.count(LogLevel::warning, "link", "lost; reconnecting"), 1u);
  r.wire.up = true;
  r.run();
  EXPECT_EQ(log.count(LogLevel::notice, "link", "connected (holding mesh version 2)"), 1u);
  EXPECT_EQ(log.count(LogLevel::warning, "replica", "rejected"), 0u);
}

TEST(BridgeAppLog, ARejectedChangeSetIsAWarning) {
  RecordingLog log(LogLevel::debug);
  test_support::BridgeLinkRig r(log);
  r.run();
  r.stroke(0.15);
  r.link->poll(*r.station.session, r.station.now_us);
  r.wire.a_to_b.flip(r.wire.a_to_b.size() / 2, std::byte{0x5a});
  r.run(40);
  EXPECT_GE(log.count(LogLevel::warning, "replica", "mesh change set rejected"), 1u);
}

TEST(BridgeAppLog, LinesAboveTheThresholdAreNotWritten) {
  RecordingLog log(LogLevel::warning);
  test_support::BridgeLinkRig r(log);
  r.run();
  r.stroke(0.1);
  r.run();
  r.wire.cut();
  r.run(3);
  ASSERT_EQ(log.lines.size(), 1u);
  EXPECT_EQ(log.lines[0].level, LogLevel::warning);
  EXPECT_EQ(log.lines[0].text, "lost; reconnecting");
}

}  // namespace
}  // namespace twister::bridge
