// Fastrak record encoder: the inverse of FastrakParser, used by the device model and
// the round-trip tests (layouts: docs/fastrak-protocol.md §3). Writes into a caller
// span; no heap.
#pragma once

#include <cstddef>
#include <span>

#include "twister/base/result.hpp"
#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/fastrak_wire.hpp"

namespace twister::tracker {

// Encodes one data record of pose.station with that station's list in config:
// '0', station digit, pose.status, then every item from the pose's values (ASCII
// fields are rounded to their printed precision; values that do not fit are clamped
// to the field; binary16 rounds to counts and packs, §3.4). Items whose value the
// pose lacks are written as zeros.
// Returns the bytes written. resource_exhausted: `out` too small;
// invalid_argument: station out of 1..4 or not enabled, or an invalid config.
Result<std::size_t> encode_record(const FastrakPose& pose, const FastrakConfig& config,
                                  std::span<std::byte> out);

// Encodes the 55-byte status reply (§3.6) for the given state.
// resource_exhausted: `out` shorter than 55 bytes.
Result<std::size_t> encode_status(const FastrakStatus& status, std::span<std::byte> out);

}  // namespace twister::tracker
