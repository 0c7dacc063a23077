// twister-sim --buttons: a scenario's `button T LINE 0|1` lines played on a rig's GPIO
// output lines, wired to the station's button inputs (docs/hil.md). The spec mirrors
// the station's [buttons.gpiod] section, so both machines' wiring reads the same:
//
//   gpiod:CHIP:OFFSET,OFFSET,...[:active-low|:active-high][:open-drain]
//
// CHIP as the station's `chip` (name, number or /dev path); button line i (the
// scenario's LINE, the station's button i) is driven on OFFSETS[i], as the station reads
// button i from `lines[i]`; active-low (the default, like the station's
// `active_low = true`): a pressed button drives its line low. open-drain: pull low or
// let go (the station's pull-up makes the high level), as a switch to GND does.
// ButtonPlayer plays the events on the scenario's clock: microseconds since the
// simulated unit started (DeviceServer::now_us(), the clock its records are sampled
// on), each event at its scripted time rounded to the microsecond (as SimButtonSource
// plays them in process); an event that does not change its line's level is skipped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "twister/base/status.hpp"
#include "twister/hal/expected.hpp"
#include "twister/sim/scenario.hpp"

namespace twister::sim {

struct GpioButtonsSpec {
  std::string chip;
  std::vector<std::uint32_t> lines;  // button line i = lines[i]
  bool active_low = true;
  bool open_drain = false;
};
inline constexpr std::size_t kMaxGpioButtonLines = 16;

// Parses the spec above. Error invalid_argument with a message naming what is wrong.
hal::Expected<GpioButtonsSpec> parse_gpio_buttons(const std::string& spec);

class ButtonPlayer {
 public:
  // Drives button line `line` pressed (true) or released.
  using SetLine = std::function<Status(std::size_t line, bool pressed)>;

  // events sorted by time (parse_scenario does).
  explicit ButtonPlayer(std::vector<ButtonEvent> events);

  // Error invalid_argument when an event names a line beyond line_count (not wired).
  hal::Expected<void> check_lines(std::size_t line_count) const;
  // Plays every event due at now_us (scenario clock). Stops at the first failure of
  // `set` and returns it (that event is not retried).
  Status advance(std::int64_t now_us, const SetLine& set);

  std::uint64_t edges() const { return edges_; }
  std::size_t remaining() const { return events_.size() - next_; }

 private:
  std::vector<ButtonEvent> events_;
  std::size_t next_ = 0;
  std::vector<bool> level_ = std::vector<bool>(kMaxScenarioButtonLines, false);
  std::uint64_t edges_ = 0;
};

}  // namespace twister::sim
