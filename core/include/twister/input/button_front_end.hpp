// ButtonFrontEnd: raw button edges in, per-hand role levels and commands out. A
// ButtonDebouncer in front of a ButtonMap: feed() takes edges as they arrive (any
// time), poll(now) applies every debounced change due by `now`: a press resolves to a
// chord or the line's own binding (ButtonMap::resolve, with the lines held at that
// moment) and either raises a level or fires a command; the release lowers the level
// that press raised. Levels then stay as they are until the next poll; commands() are
// those of the last poll. Time in microseconds, monotonic. No allocation.
// set_connected(false) (the button device is gone) releases every line at once, with
// no command and no debounce wait: what the device's buttons did meanwhile is unknown,
// so their levels start again from released when it is back.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/inline_vector.hpp"
#include "twister/base/status.hpp"
#include "twister/input/button_debouncer.hpp"
#include "twister/input/button_map.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/clock.hpp"

namespace twister::input {

// A command role (undo, redo, method_cycle) fired by a press of `hand`'s button.
struct ButtonCommand {
  std::uint8_t hand = 0;
  ButtonRole role = ButtonRole::none;
};
inline constexpr std::size_t kMaxButtonCommandsPerPoll = 8;

class ButtonFrontEnd {
 public:
  ButtonFrontEnd(const ButtonDebouncerConfig& debounce, const ButtonMap& map);

  // Raw edge from a ports::ButtonSource. out_of_range: unknown line (ignored).
  Status feed(const ports::ButtonEdge& edge);
  // Applies the debounced changes due at `now_us`, lowest line first.
  void poll(ports::TimestampUs now_us);

  // Levels of `hand` (< kHandCount) as of the last poll.
  const HandButtons& hand(std::uint8_t hand) const { return levels_[hand]; }
  // Commands fired by the last poll, in order (beyond kMaxButtonCommandsPerPoll in
  // one poll: dropped, counted).
  std::span<const ButtonCommand> commands() const { return commands_; }
  std::size_t commands_dropped() const { return commands_dropped_; }
  // Debounced lines down (bit per line) as of the last poll.
  std::uint16_t held_lines() const { return held_; }
  const ButtonMap& map() const { return map_; }
  // Whether the button device is there (set by the station from ButtonSource::connected()).
  void set_connected(bool connected);
  bool connected() const { return connected_; }

 private:
  void press(std::uint8_t line);
  void release(std::uint8_t line);

  ButtonDebouncer debouncer_;
  ButtonMap map_;
  std::array<HandButtons, kHandCount> levels_{};
  std::uint16_t held_ = 0;
  // What each held line's press resolved to (its release undoes exactly that).
  std::array<ButtonBinding, kMaxButtonLines> pressed_as_{};
  InlineVector<ButtonCommand, kMaxButtonCommandsPerPoll> commands_;
  std::size_t commands_dropped_ = 0;
  bool connected_ = true;
};

}  // namespace twister::input
