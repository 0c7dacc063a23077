// SimButtonSource: the ButtonSource port playing a scenario's `button t line 0|1`
// events (Scenario::buttons) on the same clock as SimFastrakStream, so a
// simulated run can press any ButtonMap line (both hands' grab, radius, move/freeze).
// Scenario time 0 is start_us on the clock (the instant the simulated device powers
// up). poll() returns, oldest first, each event whose time has come; an event that
// does not change the line's level is skipped (the port reports edges). Edges carry
// the scripted time, not the poll time. Errors: unavailable when nothing is due.
// PollSource: no descriptor (the loop's clock paces it); reopen() has nothing to do.
// poll() never allocates.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "twister/hal/poll_source.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/clock.hpp"
#include "twister/sim/scenario.hpp"

namespace twister::sim {

class SimButtonSource final : public ports::ButtonSource, public hal::PollSource {
 public:
  // clock must outlive the source. events must be sorted by time (parse_scenario
  // does). line_count: lines reported by line_count(), at least 1 + the highest
  // scripted line; clamped to kMaxScenarioButtonLines.
  SimButtonSource(ports::Clock& clock, std::vector<ButtonEvent> events, ports::TimestampUs start_us,
                  std::uint8_t line_count);

  // Events not yet played.
  std::size_t remaining() const { return events_.size() - next_; }

 private:
  Result<ports::ButtonEdge> do_poll() override;
  std::uint8_t do_line_count() const override { return line_count_; }
  std::size_t do_poll_fds(std::span<pollfd>) const override { return 0; }
  Status do_reopen() override { return ok_status(); }

  ports::Clock& clock_;
  std::vector<ButtonEvent> events_;
  std::size_t next_ = 0;
  ports::TimestampUs start_us_;
  std::uint8_t line_count_;
  std::array<bool, kMaxScenarioButtonLines> level_{};
};

}  // namespace twister::sim
