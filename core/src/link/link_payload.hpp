// Body serialisation of each message type (private to the link codec).
#pragma once

#include "twister/base/internal/byte_cursor.hpp"
#include "twister/link/link_message.hpp"

namespace twister::link::internal {

using twister::internal::ByteReader;
using twister::internal::ByteWriter;

// false: a count above its capacity or a field out of range.
bool write_body(ByteWriter& w, const LinkMessage& m);
// false: unknown type, short/long body or a field out of range.
bool read_body(ByteReader& r, LinkMessage& m);

}  // namespace twister::link::internal
