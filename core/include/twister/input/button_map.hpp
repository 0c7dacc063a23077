// ButtonMap: which debounced button line means what for which hand.
// Roles per hand are levels or commands. Levels are held: grab (hold to warp),
// radius (held on both hands: the distance between the hands scales the radius),
// freeze (the clutch: press while grabbing to commit and let the hand move freely,
// release to grab on from where the hand is, same weights), move_object (hold to move
// the whole model rigidly with this hand). Commands fire once per press: undo, redo,
// method_cycle (the next warp method), symmetry_cycle (the next symmetry group).
// A line has at most one role of its own. A chord binds a role to several lines:
// hold every line but the last, then press the last (the trigger); the trigger then
// acts as the chord's role instead of its own until it is released (its own role
// never sees that press). Held lines keep their own roles. Example: hold freeze, press
// grab = undo; grabbing first and then pressing freeze is still a freeze.
// Default, three buttons per hand as on the paper's station (lines 0-2 hand 0,
// lines 3-5 hand 1): hand 0 (non-dominant) grab, radius, move_object;
// hand 1 (dominant, the one that twists) grab, radius, freeze; and the chord hold
// line 4 (right radius), press line 5 (right freeze) = symmetry_cycle.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/inline_vector.hpp"
#include "twister/base/result.hpp"
#include "twister/input/button_debouncer.hpp"

namespace twister::input {

inline constexpr std::uint8_t kHandCount = 2;

enum class ButtonRole : std::uint8_t {
  none = 0,
  grab,
  radius,
  freeze,
  move_object,
  undo,
  redo,
  method_cycle,
  symmetry_cycle,
};
inline constexpr std::uint8_t kButtonRoleCount = 9;

// undo, redo, method_cycle and symmetry_cycle fire on the press; the others are held
// levels.
constexpr bool is_command(ButtonRole role) {
  return role == ButtonRole::undo || role == ButtonRole::redo || role == ButtonRole::method_cycle ||
         role == ButtonRole::symmetry_cycle;
}
// "none", "grab", "radius", "freeze", "move_object", "undo", "redo", "method_cycle",
// "symmetry_cycle".
const char* button_role_name(ButtonRole role);

inline constexpr std::size_t kMaxChords = 8;
inline constexpr std::size_t kMaxChordLines = 3;  // at most two held lines + the trigger

struct ButtonBinding {
  std::uint8_t hand = 0;
  ButtonRole role = ButtonRole::none;
};

struct ButtonChord {
  std::uint16_t held = 0;    // bit per line that must be held
  std::uint8_t trigger = 0;  // the line whose press completes the chord
  ButtonBinding binding{};
};

// Levels of every role of every hand, after mapping.
struct HandButtons {
  bool grab = false;
  bool radius = false;
  bool freeze = false;
  bool move_object = false;
};

class ButtonMap {
 public:
  // The three-buttons-per-hand default described above.
  static ButtonMap paper_default();

  // Binds a line to a role of its own (level or command). out_of_range: line >=
  // kMaxButtonLines or hand >= kHandCount.
  Status bind(std::uint8_t line, std::uint8_t hand, ButtonRole role);
  // Binds a chord: `lines` = the held lines, then the trigger (2..kMaxChordLines
  // lines). out_of_range: a line or the hand out of range; invalid_argument: too few
  // or too many lines, a line twice, role none, or the same chord bound already;
  // resource_exhausted: kMaxChords chords bound.
  Status bind_chord(std::span<const std::uint8_t> lines, std::uint8_t hand, ButtonRole role);

  // The binding of a line; role none when unbound or out of range.
  ButtonBinding binding(std::uint8_t line) const;
  // What a press of `line` means while the lines of `held` are down: the chord it
  // triggers (the one with the most held lines when several match), else the line's
  // own binding.
  ButtonBinding resolve(std::uint8_t line, std::uint16_t held) const;
  std::span<const ButtonChord> chords() const { return chords_; }

  // Applies one debounced event of a line's own level role to the per-hand levels
  // (unbound lines, command roles and chords are ignored: see ButtonFrontEnd).
  void apply(const ButtonEvent& event, std::array<HandButtons, kHandCount>& levels) const;
  // Sets the level of a level role `binding` (commands and none: no effect).
  static void set_level(const ButtonBinding& binding, bool pressed,
                        std::array<HandButtons, kHandCount>& levels);

 private:
  std::array<ButtonBinding, kMaxButtonLines> lines_{};
  InlineVector<ButtonChord, kMaxChords> chords_;
};

}  // namespace twister::input
