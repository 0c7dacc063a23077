#include "twister/input/button_map.hpp"

#include <bit>

namespace twister::input {

const char* button_role_name(ButtonRole role) {
  switch (role) {
    case ButtonRole::none:
      return "none";
    case ButtonRole::grab:
      return "grab";
    case ButtonRole::radius:
      return "radius";
    case ButtonRole::freeze:
      return "freeze";
    case ButtonRole::move_object:
      return "move_object";
    case ButtonRole::undo:
      return "undo";
    case ButtonRole::redo:
      return "redo";
    case ButtonRole::method_cycle:
      return "method_cycle";
    case ButtonRole::symmetry_cycle:
      return "symmetry_cycle";
  }
  return "unknown";
}

ButtonMap ButtonMap::paper_default() {
  ButtonMap map;
  map.bind(0, 0, ButtonRole::grab).ignore();
  map.bind(1, 0, ButtonRole::radius).ignore();
  map.bind(2, 0, ButtonRole::move_object).ignore();
  map.bind(3, 1, ButtonRole::grab).ignore();
  map.bind(4, 1, ButtonRole::radius).ignore();
  map.bind(5, 1, ButtonRole::freeze).ignore();
  // Hold the right radius, press the right freeze: the next symmetry group. Radius
  // alone does nothing and freeze alone does nothing from idle; while grabbing the
  // press is the chord's (refused: a stroke keeps its group), not the clutch.
  const std::uint8_t symmetry_chord[] = {4, 5};
  map.bind_chord(symmetry_chord, 1, ButtonRole::symmetry_cycle).ignore();
  return map;
}

Status ButtonMap::bind(std::uint8_t line, std::uint8_t hand, ButtonRole role) {
  if (line >= kMaxButtonLines || hand >= kHandCount) return StatusCode::out_of_range;
  lines_[line] = ButtonBinding{hand, role};
  return ok_status();
}

Status ButtonMap::bind_chord(std::span<const std::uint8_t> lines, std::uint8_t hand,
                             ButtonRole role) {
  if (lines.size() < 2 || lines.size() > kMaxChordLines || role == ButtonRole::none) {
    return StatusCode::invalid_argument;
  }
  if (hand >= kHandCount) return StatusCode::out_of_range;
  ButtonChord chord;
  chord.trigger = lines.back();
  chord.binding = ButtonBinding{hand, role};
  for (const std::uint8_t line : lines) {
    if (line >= kMaxButtonLines) return StatusCode::out_of_range;
  }
  for (const std::uint8_t line : lines.first(lines.size() - 1)) {
    const auto bit = static_cast<std::uint16_t>(1u << line);
    if ((chord.held & bit) != 0 || line == chord.trigger) return StatusCode::invalid_argument;
    chord.held = static_cast<std::uint16_t>(chord.held | bit);
  }
  for (const ButtonChord& c : chords()) {
    if (c.held == chord.held && c.trigger == chord.trigger) return StatusCode::invalid_argument;
  }
  return chords_.push_back(chord);  // resource_exhausted: kMaxChords chords bound
}

ButtonBinding ButtonMap::binding(std::uint8_t line) const {
  if (line >= kMaxButtonLines) return {};
  return lines_[line];
}

ButtonBinding ButtonMap::resolve(std::uint8_t line, std::uint16_t held) const {
  const ButtonChord* best = nullptr;
  for (const ButtonChord& c : chords()) {
    if (c.trigger != line || (c.held & held) != c.held) continue;
    if (best == nullptr || std::popcount(c.held) > std::popcount(best->held)) best = &c;
  }
  return best != nullptr ? best->binding : binding(line);
}

void ButtonMap::apply(const ButtonEvent& event, std::array<HandButtons, kHandCount>& levels) const {
  set_level(binding(event.line), event.pressed, levels);
}

void ButtonMap::set_level(const ButtonBinding& b, bool pressed,
                          std::array<HandButtons, kHandCount>& levels) {
  if (b.hand >= kHandCount) return;
  HandButtons& h = levels[b.hand];
  switch (b.role) {
    case ButtonRole::grab:
      h.grab = pressed;
      return;
    case ButtonRole::radius:
      h.radius = pressed;
      return;
    case ButtonRole::freeze:
      h.freeze = pressed;
      return;
    case ButtonRole::move_object:
      h.move_object = pressed;
      return;
    case ButtonRole::none:
    case ButtonRole::undo:
    case ButtonRole::redo:
    case ButtonRole::method_cycle:
    case ButtonRole::symmetry_cycle:
      return;
  }
}

}  // namespace twister::input
