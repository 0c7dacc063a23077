// Fastrak host commands (docs/fastrak.md): the one encoder/decoder pair the station's
// session (which sends them) and the simulator (which answers them) share, so no side
// spells a command letter or its syntax on its own. Two shapes (a sum type):
//   Mode        one byte, acts at once: `P C c F f U u S W T D d` and ^Y ^K ^S ^Q;
//   Parameters  a letter, comma-separated fields as text, CR: `O l H A R B b G N e I x v
//               Q X o` (`O1,2,4,1<CR>`; `O1<CR>` reads back; an empty field keeps a value).
// The codec owns letters and framing; the meaning of a field (a station, an item code, a
// filter value) belongs to the builders below (what the session sends) and to the
// simulator (what it accepts, and the error codes it answers with). No heap.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <variant>

#include "twister/base/result.hpp"
#include "twister/tracker/fastrak_wire.hpp"

namespace twister::tracker {

// Longest encoded command (letter, fields, CR): `O` with 32 two-digit items is 99 bytes.
inline constexpr std::size_t kMaxCommandBytes = 128;
inline constexpr std::size_t kMaxCommandText = kMaxCommandBytes - 2;  // without letter and CR

// The single-byte commands.
enum class ModeCommand : char {
  poll = 'P',                    // one record per active station
  continuous = 'C',              // stream records
  polled = 'c',                  // stop streaming
  ascii = 'F',                   // ASCII records
  binary = 'f',                  // binary records (IEEE, or 16-bit packed on such units)
  inches = 'U',                  // units: inches
  centimetres = 'u',             // units: centimetres
  status = 'S',                  // the 55-byte status record
  factory_defaults = 'W',        // back to the factory settings
  built_in_test = 'T',           // built-in-test information
  metal_compensation_on = 'D',   // fixed-metal compensation on
  metal_compensation_off = 'd',  // and off
  reinitialise = kCtrlY,         // as at power-up (slow)
  save = kCtrlK,                 // configuration to EEPROM
  suspend = kCtrlS,              // XOFF
  resume = kCtrlQ,               // XON
};

// The parameter commands (letter, fields, CR).
enum class ParameterCommand : char {
  output_list = 'O',          // s,i1,...,in
  station_state = 'l',        // s,state
  hemisphere = 'H',           // s,p1,p2,p3
  alignment = 'A',            // s,origin,+x point,+y point
  reset_alignment = 'R',      // s
  boresight = 'B',            // s
  unboresight = 'b',          // s
  boresight_reference = 'G',  // s,az,el,roll
  tip_offset = 'N',           // s,x,y,z
  stylus_mode = 'e',          // s,function
  increment = 'I',            // s,distance
  position_filter = 'x',      // F,FLOW,FHIGH,FACTOR | macro | read-back
  attitude_filter = 'v',      // the same for the attitude
  envelope = 'Q',             // s,azmax,elmax,rlmax,azmin,elmin,rlmin
  user_id = 'X',              // a 32-character string
  serial_port = 'o',          // rate,parity,bits,HHS
};

struct Mode {
  ModeCommand command = ModeCommand::status;
  friend bool operator==(const Mode&, const Mode&) = default;
};

// A parameter command: its fields as sent (commas included, no CR). Any byte but CR and
// LF may be in a field: what it means is the receiver's business.
struct Parameters {
  ParameterCommand command = ParameterCommand::output_list;
  std::array<char, kMaxCommandText> text{};
  std::uint8_t length = 0;

  std::string_view fields() const { return {text.data(), length}; }
  // 1 + the number of commas (no text is one empty field: a read-back).
  std::size_t field_count() const;
  // Field i (0-based), empty past the last.
  std::string_view field(std::size_t i) const;
  // Appends to the text; false (text unchanged beyond what fit) when it does not fit
  // or holds a CR or LF.
  bool append(std::string_view more);
  bool append_int(int value);
  friend bool operator==(const Parameters& a, const Parameters& b) {
    return a.command == b.command && a.fields() == b.fields();
  }
};

using FastrakCommand = std::variant<Mode, Parameters>;

// The command a first byte starts, if any.
std::optional<ModeCommand> mode_command(char byte);
std::optional<ParameterCommand> parameter_command(char byte);
char letter(const FastrakCommand& command);

// The unit's adaptive filter (`x` position, `v` attitude): left as the unit has it
// (EEPROM), switched off (`x,1`: FLOW = 1 disables it), or set to the four parameters
// (the manual's "medium" is 0.2, 0.2, 0.8, 0.95). Each value 0..1, sent with three
// decimals.
struct FilterSetting {
  enum class Mode : std::uint8_t { leave, off, set };
  Mode mode = Mode::leave;
  float f = 0.2f;
  float flow = 0.2f;
  float fhigh = 0.8f;
  float factor = 0.95f;
};

// What the session sends. Each fits (stations 1..4, at most kMaxItems items).
Parameters station_state_command(int station, bool enabled);                   // l1,1
Parameters output_list_command(int station, const OutputList& list);           // O1,2,4,1
Parameters hemisphere_command(int station, const std::array<int, 3>& toward);  // H1,1,0,0
Parameters stylus_mode_command(int station, int function);                     // e1,0
// x / v of `setting` (nullopt for Mode::leave): `x,1` off, `x0.200,0.200,0.800,0.950`.
std::optional<Parameters> filter_command(ParameterCommand which, const FilterSetting& setting);

// The command's bytes into `out`; returns how many. resource_exhausted: `out` too small.
Result<std::size_t> encode(const FastrakCommand& command, std::span<char> out);

// Exactly one command: a mode byte alone, or a parameter letter, its fields and CR.
// invalid_argument: empty, an unknown first byte, bytes after a mode byte or the CR,
// no CR, or an LF in the fields; resource_exhausted: fields longer than kMaxCommandText.
Result<FastrakCommand> decode(std::span<const char> bytes);

}  // namespace twister::tracker
