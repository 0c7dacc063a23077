#include "twister/input/button_map.hpp"

namespace twister::input {

ButtonMap ButtonMap::paper_default() {
  ButtonMap map;
  map.bind(0, 0, ButtonRole::grab).ignore();
  map.bind(1, 0, ButtonRole::radius).ignore();
  map.bind(2, 0, ButtonRole::move_object).ignore();
  map.bind(3, 1, ButtonRole::grab).ignore();
  map.bind(4, 1, ButtonRole::radius).ignore();
  map.bind(5, 1, ButtonRole::freeze).ignore();
  return map;
}

Status ButtonMap::bind(std::uint8_t line, std::uint8_t hand, ButtonRole role) {
  if (line >= kMaxButtonLines || hand >= kHandCount) return StatusCode::out_of_range;
  lines_[line] = ButtonBinding{hand, role};
  return ok_status();
}

ButtonBinding ButtonMap::binding(std::uint8_t line) const {
  if (line >= kMaxButtonLines) return {};
  return lines_[line];
}

void ButtonMap::apply(const ButtonEvent& event, std::array<HandButtons, kHandCount>& levels) const {
  const ButtonBinding b = binding(event.line);
  if (b.hand >= kHandCount) return;
  HandButtons& h = levels[b.hand];
  switch (b.role) {
    case ButtonRole::none:
      return;
    case ButtonRole::grab:
      h.grab = event.pressed;
      return;
    case ButtonRole::radius:
      h.radius = event.pressed;
      return;
    case ButtonRole::freeze:
      h.freeze = event.pressed;
      return;
    case ButtonRole::move_object:
      h.move_object = event.pressed;
      return;
  }
}

}  // namespace twister::input
