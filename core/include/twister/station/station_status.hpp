// StationStatus: a snapshot of what the display shows about the station besides
// the mesh and the hands (tracker state and rate, counters, method, clutch, the
// angle turned against the limit, refinement stopped by the capacity, the button
// device missing), filled by
// Station::status() from the session's state and sent by StationLink. Plain data.
#pragma once

#include <cstdint>

#include "twister/math/warp_method.hpp"

namespace twister::station {

enum class TrackerLinkState : std::uint8_t { starting = 0, streaming = 1, lost = 2 };

struct StationStatus {
  TrackerLinkState tracker = TrackerLinkState::starting;
  float tracker_rate_hz = 0.0F;  // poses used per second, both hands (1 s window)
  std::uint64_t strokes_committed = 0;
  std::uint64_t strokes_not_saved = 0;
  math::WarpMethod method = math::WarpMethod::twister;  // of the next stroke
  std::uint8_t clutch = 0;           // bit h: hand h's clutch is in (freeze held, disengaged)
  float turned_rad = 0.0F;           // the most any hand has turned in the open stroke
  float turn_limit_rad = 0.0F;       // one stroke's turn limit
  std::uint64_t capacity_stops = 0;  // refined commits stopped by the mesh's capacity
  bool buttons_missing = false;      // the button device is not there (ButtonSource::connected())
};

}  // namespace twister::station
