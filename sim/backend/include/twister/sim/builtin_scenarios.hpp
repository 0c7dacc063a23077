// Built-in simulator scenarios selectable from station.toml ([tracker.sim] scenario):
// Positions stay in the source's +X hemisphere (the unit mirrors the other half).
//   stroke - receiver 1's stylus pressed at 4.0 s at (10, -8, 5) in, the receiver
//            moves to (14, -6, 5) in between 4.5 s and 5.5 s, released at 6.0 s: one
//            stroke; 7.5 s long.
//   idle   - both receivers still, no stylus press; 3 s long.
//   unplug - the stroke above; the stylus is pressed again at 6.8 s and the line hangs
//            up at 7.0 s for 1.5 s (mid-stroke: the station must cancel it; the unit
//            streams on behind the pulled line); a second stroke from (14, -6, 5) in to (18, -4, 5)
//            in runs from 12.5 s to 14.5 s; 16 s long. The same scenarios for
//            twister-sim: tests/hal/twister-station/scenarios/pty_{stroke,unplug}.txt.
#pragma once

#include <string>
#include <string_view>

#include "twister/hal/expected.hpp"
#include "twister/sim/scenario.hpp"

namespace twister::sim {

// The scenario text of a built-in name; empty view for an unknown name.
std::string_view builtin_scenario_text(std::string_view name);

// Parses a built-in scenario (start-up). invalid_argument: unknown name.
hal::Expected<Scenario> load_builtin_scenario(std::string_view name);

}  // namespace twister::sim
