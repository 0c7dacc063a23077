// Built-in simulator scenarios selectable from station.toml ([tracker.sim] scenario):
// Positions stay in the source's +X hemisphere (the unit mirrors the other half).
//   stroke - receiver 1's stylus pressed from 4.0 s to 5.0 s while the receiver moves
//            from (10, -8, 5) in to (14, -6, 5) in: one stroke; 7 s long.
//   idle   - both receivers still, no stylus press; 3 s long.
//   unplug - the stroke above, the line hangs up at 6.0 s for 1.0 s, the unit powers
//            up again, and a second stylus stroke from (14, -6, 5) in to (18, -4, 5) in
//            runs from 11.0 s to 12.0 s; 14 s long.
#pragma once

#include <string>
#include <string_view>

#include "twister/sim/scenario.hpp"

namespace twister::hal {

// The scenario text of a built-in name; empty view for an unknown name.
std::string_view builtin_scenario_text(std::string_view name);

// Parses a built-in scenario. false (and error set) for an unknown name.
bool load_builtin_scenario(std::string_view name, sim::Scenario& out, std::string& error);

}  // namespace twister::hal
