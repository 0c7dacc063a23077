// Body serialisation of each message type (private to the link codec).
#pragma once

#include "twister/base/internal/byte_cursor.hpp"
#include "twister/link/link_message.hpp"

namespace twister::link::internal {

using twister::internal::ByteReader;
using twister::internal::ByteWriter;

// One writer per message type; false: a count above its capacity or a field out
// of range.
bool write_body(ByteWriter& w, const Hello& m);
bool write_body(ByteWriter& w, const Auth& m);
bool write_body(ByteWriter& w, const Bye& m);
bool write_body(ByteWriter& w, const MeshBegin& m);
bool write_body(ByteWriter& w, const Vertices& m);
bool write_body(ByteWriter& w, const Triangles& m);
bool write_body(ByteWriter& w, const MeshEnd& m);
bool write_body(ByteWriter& w, const ResendRequest& m);
bool write_body(ByteWriter& w, const StrokeBegin& m);
bool write_body(ByteWriter& w, const Hands& m);
bool write_body(ByteWriter& w, const ObjectPose& m);
bool write_body(ByteWriter& w, const StatusReport& m);
bool write_body(ByteWriter& w, const Command& m);
bool write_body(ByteWriter& w, const Workspace& m);
bool write_body(ByteWriter& w, const VisitorState& m);
bool write_body(ByteWriter& w, const Notice& m);

// Reads the body of a `type` message into `m` (which then holds that
// alternative); false: short/long body or a field out of range.
bool read_body(ByteReader& r, MessageType type, LinkMessage& m);

}  // namespace twister::link::internal
