// ButtonFrontEnd: raw button edges in, per-hand role levels out. A ButtonDebouncer
// in front of a ButtonMap: feed() takes edges as they arrive (any time), poll(now)
// applies every debounced change due by `now` to the levels, which then stay as they
// are until the next poll. Time in microseconds, monotonic. No allocation.
#pragma once

#include <array>
#include <cstdint>

#include "twister/base/status.hpp"
#include "twister/input/button_debouncer.hpp"
#include "twister/input/button_map.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/clock.hpp"

namespace twister::input {

class ButtonFrontEnd {
 public:
  ButtonFrontEnd(const ButtonDebouncerConfig& debounce, const ButtonMap& map);

  // Raw edge from a ports::ButtonSource. out_of_range: unknown line (ignored).
  Status feed(const ports::ButtonEdge& edge);
  // Applies the debounced changes due at `now_us`, lowest line first.
  void poll(ports::TimestampUs now_us);

  // Levels of `hand` (< kHandCount) as of the last poll.
  const HandButtons& hand(std::uint8_t hand) const { return levels_[hand]; }

 private:
  ButtonDebouncer debouncer_;
  ButtonMap map_;
  std::array<HandButtons, kHandCount> levels_{};
};

}  // namespace twister::input
