// Body serialisation of each message type (private to the link codec).
#pragma once

#include "payload_io.hpp"
#include "twister/link/link_message.hpp"

namespace twister::link::internal {

// false: a count above its capacity or a field out of range.
bool write_body(PayloadWriter& w, const LinkMessage& m);
// false: unknown type, short/long body or a field out of range.
bool read_body(PayloadReader& r, LinkMessage& m);

}  // namespace twister::link::internal
