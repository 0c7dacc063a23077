// Scenario for the simulated Fastrak: hand trajectories (key frames or circles per
// station), stylus presses, and timed fault injections. Text format in docs/fastrak.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "twister/hal/expected.hpp"

namespace twister::sim {

// One key frame: time, position (inches, tracker frame), Euler angles (degrees),
// stylus state. Between keys position and angles are interpolated linearly; the
// button holds its value until the next key.
struct KeyFrame {
  double t_s = 0.0;
  std::array<double, 3> position_in{};
  std::array<double, 3> euler_deg{};
  bool button = false;
};

// A circle in the tracker's x-y plane around `center_in`, one turn per period; the
// azimuth follows the direction of travel.
struct Circle {
  bool enabled = false;
  std::array<double, 3> center_in{};
  double radius_in = 0.0;
  double period_s = 1.0;
};

enum class FaultKind : std::uint8_t {
  noise,       // `amount` random bytes injected into the output
  drop,        // the next `amount` output bytes are lost
  truncate,    // the next `amount` records are cut short
  stall,       // no output and no command processing for `amount` seconds
  hangup,      // the line is down for `amount` seconds; the unit runs on behind it
  wrong_baud,  // for `amount` seconds the line is mis-clocked (baud mismatch): mostly
               // silence, occasional junk, both directions
  corrupt,     // the next `amount` records each get one number field corrupted inside
               // the record (digit, sign or float bit; syntax and framing intact)
};
inline constexpr std::size_t kFaultKindCount = 7;
// The kind's keyword in the scenario text (parse_scenario reads these names).
const char* fault_kind_name(FaultKind k);

struct Fault {
  double t_s = 0.0;
  FaultKind kind = FaultKind::noise;
  double amount = 0.0;
};

// A scripted level change of a button line (0-based, the station's ButtonMap line:
// by default 0-2 hand 0 grab/radius/move, 3-5 hand 1 grab/radius/freeze). Played by
// sim::SimButtonSource, not by the Fastrak model (those lines are not on the tracker).
inline constexpr int kMaxScenarioButtonLines = 16;
struct ButtonEvent {
  double t_s = 0.0;
  int line = 0;  // 0..kMaxScenarioButtonLines-1
  bool pressed = false;
};

// A scripted header status byte (docs/fastrak-protocol.md §3.1): records of `station` carry `code`
// (a letter: a warning the host must accept) from t_s for duration_s.
struct StatusEvent {
  double t_s = 0.0;
  int station = 1;
  char code = ' ';
  double duration_s = 0.0;
};

struct StationTrack {
  std::vector<KeyFrame> keys;  // sorted by time
  Circle circle;
};

struct Scenario {
  std::uint32_t seed = 1;
  int receivers = 2;        // receivers plugged in (stations 1..receivers)
  double duration_s = 0.0;  // 0 = run until stopped
  std::array<StationTrack, 4> stations;
  std::vector<Fault> faults;         // sorted by time
  std::vector<ButtonEvent> buttons;  // sorted by time (stable: file order at equal times)
  std::vector<StatusEvent> status;   // header status letters, in file order
};

// Sample of one station at a time.
struct HandSample {
  std::array<double, 3> position_in{};
  std::array<double, 3> euler_deg{};
  bool button = false;
};

// Position/orientation/button of `station` (1..4) at t_s.
HandSample sample(const Scenario& scenario, int station, double t_s);

// Limits of what a scenario may ask for (beyond them it is refused with a message
// naming the line and the range): times and durations, fault amounts per kind,
// positions and angles; and of a scenario file: its size and line length.
inline constexpr double kMaxScenarioSeconds = 1e6;  // 11.6 days
inline constexpr double kMaxNoiseBytes = 1e6;       // noise: bytes injected
inline constexpr double kMaxDropBytes = 1e8;        // drop: bytes lost
inline constexpr double kMaxFaultRecords = 1e6;     // truncate, corrupt: records
inline constexpr double kMaxFaultSeconds = 3600.0;  // stall, hangup, wrongbaud
inline constexpr double kMaxPositionIn = 1000.0;    // key and circle positions (inches)
inline constexpr double kMaxAngleDeg = 1e4;         // key angles (degrees)
inline constexpr std::uint64_t kMaxScenarioBytes = std::uint64_t{16} << 20;  // 16 MiB
inline constexpr std::size_t kMaxScenarioLineBytes = 4096;

// Parses the text format. On error returns false and sets `error` to
// "line N: message".
bool parse_scenario(std::string_view text, Scenario& out, std::string& error);

// Reads and parses a scenario file (start-up), line by line through a fixed buffer:
// memory is what the scenario holds, not the file. The file is opened O_NONBLOCK
// and must be a regular file of at most kMaxScenarioBytes. Errors: io_error
// "cannot read scenario file PATH: why", "scenario file PATH is a FIFO (a device, a
// directory), not a regular file"; invalid_argument "scenario file PATH is N bytes;
// scenarios are limited to ...", "PATH: line N: message".
hal::Expected<Scenario> load_scenario_file(const std::string& path);

}  // namespace twister::sim
