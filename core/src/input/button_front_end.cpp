#include "twister/input/button_front_end.hpp"

namespace twister::input {

ButtonFrontEnd::ButtonFrontEnd(const ButtonDebouncerConfig& debounce, const ButtonMap& map)
    : debouncer_(debounce), map_(map) {}

Status ButtonFrontEnd::feed(const ports::ButtonEdge& edge) { return debouncer_.feed(edge); }

void ButtonFrontEnd::poll(ports::TimestampUs now_us) {
  commands_.clear();
  for (auto e = debouncer_.poll(now_us); e.ok(); e = debouncer_.poll(now_us)) {
    if (e->line >= kMaxButtonLines) continue;
    if (e->pressed) {
      press(e->line);
    } else {
      release(e->line);
    }
  }
}

void ButtonFrontEnd::set_connected(bool connected) {
  if (connected == connected_) return;
  connected_ = connected;
  if (connected) return;
  debouncer_.reset();
  held_ = 0;
  levels_ = {};
  pressed_as_ = {};
}

void ButtonFrontEnd::press(std::uint8_t line) {
  const auto bit = static_cast<std::uint16_t>(1u << line);
  const ButtonBinding b = map_.resolve(line, static_cast<std::uint16_t>(held_ & ~bit));
  held_ = static_cast<std::uint16_t>(held_ | bit);
  pressed_as_[line] = b;
  if (!is_command(b.role)) {
    ButtonMap::set_level(b, true, levels_);
    return;
  }
  if (!commands_.push_back(ButtonCommand{b.hand, b.role}).ok()) ++commands_dropped_;
}

void ButtonFrontEnd::release(std::uint8_t line) {
  held_ = static_cast<std::uint16_t>(held_ & ~(1u << line));
  ButtonMap::set_level(pressed_as_[line], false, levels_);
  pressed_as_[line] = ButtonBinding{};
}

}  // namespace twister::input
