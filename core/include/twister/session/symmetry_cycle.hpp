// SymmetryCycle: the groups a sculptor steps through with the symmetry_cycle button
// chord or a display's cycle_symmetry command ([sculpt] symmetry_cycle; default: none
// and the configured symmetry). next() is the group after the current one (the first
// when the current one is not in the cycle). math::symmetry_label() names a group the way the
// configuration does ("none", "x", "xz", "rot6 z", "rot6m y"). Plain data, no heap.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"
#include "twister/base/status.hpp"
#include "twister/math/symmetry.hpp"

namespace twister::session {

inline constexpr std::size_t kMaxSymmetryCycle = 8;

struct SymmetryCycle {
  std::array<math::SymmetrySpec, kMaxSymmetryCycle> groups{};
  std::uint8_t count = 0;  // 0: none and the session's configured symmetry

  // The cycle a session with `configured` uses: this one, or {none, configured}
  // (just {none} when configured is none).
  SymmetryCycle resolved(const math::SymmetrySpec& configured) const;
  // invalid_argument: full or not a valid group.
  Status push(const math::SymmetrySpec& spec);
  std::span<const math::SymmetrySpec> items() const { return {groups.data(), count}; }
  // The group after `current` (the first when `current` is not in the cycle).
  // failed_precondition: fewer than two groups (nothing to cycle to).
  Result<math::SymmetrySpec> next(const math::SymmetrySpec& current) const;
};

}  // namespace twister::session
