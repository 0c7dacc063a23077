// StationConfig: what the composition root sets up the station with (tracker session,
// pose conversion, which receiver each hand holds, the stylus as a button, the
// sculpting session, checkpoints). Plain data.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/input/button_map.hpp"
#include "twister/ports/clock.hpp"
#include "twister/session/sculpt_session.hpp"
#include "twister/station/station_exhibit.hpp"
#include "twister/tracker/fastrak_session.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::station {

struct StationConfig {
  tracker::FastrakSessionConfig session{};
  tracker::PoseConversion conversion{};
  // Fastrak receiver (1..4) held by hand 0 and hand 1.
  std::array<std::uint8_t, input::kHandCount> hand_station{1, 2};
  // A hand's pose older than this counts as not valid (tracker silent or lost).
  ports::TimestampUs pose_stale_us = 200'000;
  // Fastrak stylus switch (item 16) as a button: stylus_line[station - 1] is the
  // button line its state drives (-1 = none). The edge goes through the debouncer
  // like any ButtonSource edge, stamped with the poll time of the record.
  std::array<std::int8_t, tracker::kMaxStations> stylus_line{-1, -1, -1, -1};
  // Debounce, button map, interaction timing, warp method.
  session::SculptSessionConfig sculpt{};
  // A checkpoint is written once this many journal records were added since the last
  // one (and at stop); 0: only at stop. Written a chunk per poll(), while the model
  // stays unchanged (a commit meanwhile starts it over later).
  std::uint32_t checkpoint_interval = 256;
  std::size_t checkpoint_bytes_per_poll = std::size_t{256} << 10;
  // Exhibit mode (issue 25; off by default): the visitor lifecycle, one journal per
  // sculpture, the archive (StationFiles::archive, base_model).
  ExhibitConfig exhibit{};
};

}  // namespace twister::station
