// ButtonDebouncer: turns raw, bouncing button edges (ports::ButtonEdge) into clean
// press/release events. A level is reported once it has stayed unchanged for the
// line's debounce interval; any edge inside the interval restarts the wait.
// Pure: edges and the current time come in as arguments (microseconds, monotonic),
// nothing is read from a clock. Fixed capacity: kMaxButtonLines lines.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/inline_vector.hpp"
#include "twister/base/result.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/clock.hpp"

namespace twister::input {

inline constexpr std::size_t kMaxButtonLines = 16;

// One debounced change of a line.
struct ButtonEvent {
  std::uint8_t line = 0;
  bool pressed = false;
  ports::TimestampUs time_us = 0;  // when the level became stable (edge + interval)
};

struct ButtonDebouncerConfig {
  std::uint8_t line_count = 6;
  // Debounce interval per line in microseconds (0 = report at the next poll).
  std::array<ports::TimestampUs, kMaxButtonLines> interval_us{5000, 5000, 5000, 5000, 5000, 5000,
                                                              5000, 5000, 5000, 5000, 5000, 5000,
                                                              5000, 5000, 5000, 5000};
};

class ButtonDebouncer {
 public:
  // line_count is clamped to kMaxButtonLines; all lines start released.
  explicit ButtonDebouncer(const ButtonDebouncerConfig& config);

  // Records a raw edge. out_of_range: edge.line >= line_count (the edge is ignored).
  Status feed(const ports::ButtonEdge& edge);

  // Next debounced event that is due at `now_us` (lowest line first).
  // unavailable: nothing is due yet.
  Result<ButtonEvent> poll(ports::TimestampUs now_us);

  // The debounced (reported) level of a line; false for lines out of range.
  bool pressed(std::uint8_t line) const;

  // Every line released, stable and raw, with no change pending (the device that
  // drove them is gone: their levels are unknown).
  void reset();

  std::uint8_t line_count() const { return static_cast<std::uint8_t>(lines_.size()); }

 private:
  struct Line {
    bool stable = false;  // last reported level
    bool raw = false;     // latest raw level
    ports::TimestampUs raw_since_us = 0;
  };
  ButtonDebouncerConfig config_;
  InlineVector<Line, kMaxButtonLines> lines_;  // one per line in use
};

}  // namespace twister::input
