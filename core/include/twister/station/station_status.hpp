// StationStatus: a snapshot of what the display shows about the station besides
// the mesh and the hands (tracker state and rate, counters, method, clutch, the
// turn limit), filled by Station::status() and sent by StationLink. Fields the
// session does not report yet keep their defaults (documented in
// docs/link-protocol.md: "filled once the session reports it"). Plain data.
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
  std::uint8_t clutch = 0;      // bit h: hand h's clutch is in (filled once the session reports it)
  float turn_limit_rad = 0.0F;  // one stroke's turn limit; 0 = not reported yet
};

}  // namespace twister::station
