// UnitSettings: what the simulated Fastrak's commands set and a power-up resets (the
// protocol configuration, stream mode, stylus mode, hemispheres, envelopes, filters,
// line rate). Plain state with one job: hold the settings. No heap.
#pragma once

#include <array>

#include "twister/sim/adaptive_filter.hpp"
#include "twister/tracker/fastrak_wire.hpp"

namespace twister::sim {

// The power-up settings (switches, EEPROM).
struct PowerUpSettings {
  int baud = 115200;
  bool continuous = false;
  tracker::Format format = tracker::Format::ascii;
  int receivers = 2;  // stations 1..receivers enabled
  FilterParams position_filter = kFilterOff;
  FilterParams attitude_filter = kFilterOff;
};

struct UnitSettings {
  tracker::FastrakConfig protocol{};
  bool continuous = false;
  bool output_on = true;  // stylus point/track toggle in continuous mode
  int stylus_mode = 1;    // `e` function: 1 point/track, 0 mouse mode
  std::array<std::array<double, 3>, 4> hemisphere{};
  // `Q` angular envelope per station: az max, el max, roll max, az min, el min, roll min.
  std::array<std::array<double, 6>, 4> envelope{};
  std::array<FilterParams, 2> filter{};  // position (`x`), attitude (`v`)
  // `N` tip offset per station, inches, in the receiver's axes: the reported point is
  // the solution's position + R * offset.
  std::array<std::array<double, 3>, 4> tip_offset_in{};
  // `B` / `b` / `G` per station: a `B` asks for the next solution's attitude to be
  // captured (boresight_requests counts them; the solver captures once per request);
  // while boresight_on, attitudes are reported as R_ref * B^T * R, R_ref from the `G`
  // reference angles (az, el, roll degrees).
  std::array<bool, 4> boresight_on{};
  std::array<unsigned, 4> boresight_requests{};
  std::array<std::array<double, 3>, 4> boresight_reference_deg{};
  int baud = 115200;

  // The settings a power-up leaves (`o` is not saved: the switches' rate).
  void power_up(const PowerUpSettings& start);
};

}  // namespace twister::sim
