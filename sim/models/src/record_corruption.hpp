// In-record corruption (a line hit inside a record): one number field of an encoded
// record is changed the way a flipped bit would change it while the record keeps its
// header, length, terminator and field syntax, so framing cannot see it and only
// plausibility checks can. ASCII: a digit becomes another digit (one bit flipped
// among bits 0-3) or the sign flips; IEEE binary: one bit of a float byte; 16-bit
// packed: one bit of a count, with the record repacked so the sync bit stays valid.
// Private to the device model. No heap.
#pragma once

#include <cstddef>
#include <random>
#include <span>

#include "twister/tracker/fastrak_wire.hpp"

namespace twister::sim {

// Corrupts `record` (one encoded record of `station`'s list in `config`). false: the
// list has no number item (nothing was changed).
bool corrupt_record(std::span<std::byte> record, int station, const tracker::FastrakConfig& config,
                    std::mt19937& rng);

}  // namespace twister::sim
