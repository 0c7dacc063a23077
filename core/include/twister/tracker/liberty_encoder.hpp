// Liberty / Patriot / Latus frame encoder: the inverse of LibertyParser, for the device
// model and the round-trip tests (layout: docs/liberty-protocol.md §2-§3). Writes into a
// caller span; no heap.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"
#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/liberty_wire.hpp"

namespace twister::tracker {

// Values a frame carries that the pose type does not.
struct LibertyFrameExtras {
  char command = kLibertyContinuous;  // 'C' continuous, 'P' polled
  std::uint32_t timestamp = 0;        // item 8
  std::uint32_t frame_count = 0;      // item 9
  std::int32_t distortion = 0;        // item 11
};

// Encodes one data frame of pose.station with that station's list: the model's tag,
// station, command, error byte (0 for status ' ', else the status character), reserved 0,
// size (per config.size_field), then every item from the pose's values (missing values as
// zeros). Returns the bytes written.
// resource_exhausted: `out` too small; invalid_argument: station out of range or not
// enabled, or an invalid config.
Result<std::size_t> encode_liberty_frame(const FastrakPose& pose, const LibertyConfig& config,
                                         std::span<std::byte> out,
                                         const LibertyFrameExtras& extras = {});

}  // namespace twister::tracker
