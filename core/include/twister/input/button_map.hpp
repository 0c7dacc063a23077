// ButtonMap: which debounced button line means what for which hand.
// Roles per hand: grab (hold to warp), radius (held on both hands: the distance
// between the hands scales the radius), freeze (press while grabbing: commit and
// restart from the current poses with the same weights), move_object (hold to move
// the whole model rigidly with this hand).
// Default, three buttons per hand as on the paper's station (lines 0-2 hand 0,
// lines 3-5 hand 1): hand 0 (non-dominant) grab, radius, move_object;
// hand 1 (dominant, the one that twists) grab, radius, freeze.
#pragma once

#include <array>
#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/input/button_debouncer.hpp"

namespace twister::input {

inline constexpr std::uint8_t kHandCount = 2;

enum class ButtonRole : std::uint8_t { none = 0, grab, radius, freeze, move_object };
inline constexpr std::uint8_t kButtonRoleCount = 5;

struct ButtonBinding {
  std::uint8_t hand = 0;
  ButtonRole role = ButtonRole::none;
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

  // Binds a line. out_of_range: line >= kMaxButtonLines or hand >= kHandCount.
  Status bind(std::uint8_t line, std::uint8_t hand, ButtonRole role);

  // The binding of a line; role none when unbound or out of range.
  ButtonBinding binding(std::uint8_t line) const;

  // Applies one debounced event to the per-hand levels (unbound lines are ignored).
  void apply(const ButtonEvent& event, std::array<HandButtons, kHandCount>& levels) const;

 private:
  std::array<ButtonBinding, kMaxButtonLines> lines_{};
};

}  // namespace twister::input
