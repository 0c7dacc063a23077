// Private: the value checks of a framed record (docs/fastrak-protocol.md §3.8), in the order of the
// reasons' list. Pure; no heap.
#pragma once

#include <optional>

#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/fastrak_wire.hpp"

namespace twister::tracker::internal {

// The first failing check, or nullopt when the pose is plausible. dcm_rows: bit i set
// when row i of the direction cosines (item 5 + i) was in the list.
std::optional<PoseError> check_plausibility(const FastrakPose& pose, unsigned dcm_rows,
                                            const FastrakConfig& config);

}  // namespace twister::tracker::internal
