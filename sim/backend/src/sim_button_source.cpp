#include "twister/sim/sim_button_source.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace twister::sim {
namespace {

ports::TimestampUs event_time_us(ports::TimestampUs start_us, double t_s) {
  // Rounded to the microsecond so a press scripted at t and a tracker record at t
  // land on the same tick of a virtual clock.
  return start_us + static_cast<ports::TimestampUs>(std::llround(t_s * 1e6));
}

}  // namespace

SimButtonSource::SimButtonSource(ports::Clock& clock, std::vector<ButtonEvent> events,
                                 ports::TimestampUs start_us, std::uint8_t line_count)
    : clock_(clock), events_(std::move(events)), start_us_(start_us), line_count_(line_count) {
  int highest = -1;
  for (const ButtonEvent& e : events_) highest = std::max(highest, e.line);
  line_count_ = static_cast<std::uint8_t>(
      std::min(kMaxScenarioButtonLines, std::max(static_cast<int>(line_count_), highest + 1)));
}

Result<ports::ButtonEdge> SimButtonSource::do_poll() {
  const ports::TimestampUs now = clock_.now_us();
  while (next_ < events_.size()) {
    const ButtonEvent& e = events_[next_];
    const ports::TimestampUs t = event_time_us(start_us_, e.t_s);
    if (t > now) break;
    ++next_;
    if (e.line < 0 || e.line >= line_count_) continue;  // not a configured line
    bool& level = level_[static_cast<std::size_t>(e.line)];
    if (level == e.pressed) continue;  // no edge
    level = e.pressed;
    return ports::ButtonEdge{static_cast<std::uint8_t>(e.line), e.pressed, t};
  }
  return StatusCode::unavailable;
}

}  // namespace twister::sim
