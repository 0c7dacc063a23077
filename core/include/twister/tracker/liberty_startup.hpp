// The Liberty family's start-up as the public drivers send it (docs/liberty-protocol.md §9,
// each command with its source): the station's session sends these to a Liberty, Patriot
// or Latus, and the simulator's Liberty model reads them back, so neither spells a
// command on its own. Every command but the ladder's single `P` ends with CR; the unit
// has no Fastrak `S` status record: ^V (WhoAmI) answers with text whose first byte is
// '0' (VRPN's check). No heap.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

#include "twister/base/result.hpp"
#include "twister/tracker/fastrak_command.hpp"
#include "twister/tracker/fastrak_wire.hpp"
#include "twister/tracker/liberty_wire.hpp"

namespace twister::tracker {

inline constexpr char kCtrlV = 0x16;  // WhoAmI
inline constexpr std::string_view kLibertyWhoAmI = "\x16\r";
inline constexpr char kLibertyWhoAmIFirst = '0';  // a WhoAmI reply's first byte (VRPN)
inline constexpr std::string_view kLibertyAscii = "F0\r";
inline constexpr std::string_view kLibertyBinary = "F1\r";
inline constexpr std::string_view kLibertyInches = "U0\r";
inline constexpr std::string_view kLibertyCentimetres = "U1\r";
inline constexpr std::string_view kLibertyStartContinuous = "C\r";
// The ladder's `P` (kLibertyPoll, liberty_wire.hpp): one record; it also ends continuous output.
inline constexpr std::string_view kLatusUsbBufferingOff = "@B0\r";
inline constexpr char kLibertyPositionFilter = 'X';  // the Fastrak's `x`
inline constexpr char kLibertyAttitudeFilter = 'Y';  // the Fastrak's `v`

// The reset ladder's bytes for `rung` (1..3), sent one by one with a pause after each:
// "CR F0 CR" (back to ASCII, out of a half-typed command; the Latus without the first
// CR), at rung 3 "^Y CR" (re-initialise), then `P`. Returns how many (at most 7).
std::size_t liberty_ladder(LibertyModel family, int rung, std::span<char> out);

// `X` / `Y` for `setting` (nothing for Mode::leave: returns 0): "X0,1,0,0" off (VRPN),
// "X0.200,0.200,0.800,0.950" set, CR-terminated. resource_exhausted: `out` too small.
Result<std::size_t> encode_liberty_filter(char letter, const FilterSetting& setting,
                                          std::span<char> out);

}  // namespace twister::tracker
