// Issue 20: each link message is its own small type and LinkMessage a variant of
// them. No message type is bigger than its largest body on the wire plus its
// alignment, and the variant (what a decoder holds) is at most 1.2 x the largest
// body (label architecture).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "twister/link/link_codec.hpp"

namespace twister::link {
namespace {

// Body bytes of `m` on the wire: its payload (version, type, body) less the header.
template <LinkBody M>
std::size_t body_bytes(const M& m) {
  std::vector<std::byte> frame(kMaxFrameBytes);
  const auto n = encode_frame(m, frame);
  EXPECT_TRUE(n.ok());
  std::vector<std::byte> buffer(kMaxFrameBytes);
  FrameDecoder d(buffer);
  for (std::size_t i = 0; i < *n; ++i) {
    if (const auto payload = d.process(frame[i]); payload.ok()) return payload->size() - 2;
  }
  ADD_FAILURE() << "no frame";
  return 0;
}

// The largest instance of each type: every count at its capacity, both hands.
Vertices largest_vertices() {
  Vertices v;
  v.count = kMaxVerticesPerChunk;
  return v;
}
Triangles largest_triangles() {
  Triangles t;
  t.count = kMaxTrianglesPerChunk;
  return t;
}
StrokeBegin largest_stroke() {
  StrokeBegin s;
  s.hand_mask = 3;
  s.radius_m = 0.1;
  return s;
}
Hands largest_hands() {
  Hands h;
  h.flags = kHandSample0 | kHandSample1;
  return h;
}

template <LinkBody M>
std::size_t check(const char* name, const M& largest) {
  const std::size_t body = body_bytes(largest);
  std::printf("%-14s sizeof %5zu, largest body %5zu\n", name, sizeof(M), body);
  EXPECT_LE(sizeof(M), body + alignof(M)) << name;
  return body;
}

TEST(LinkMessageSize, EachMessageIsAsSmallAsItsBodyAndTheVariantAsItsLargest) {
  std::size_t largest = 0;
  const auto note = [&largest](std::size_t body) { largest = std::max(largest, body); };
  note(check("hello", Hello{}));
  note(check("auth", Auth{}));
  note(check("bye", Bye{}));
  note(check("mesh_begin", MeshBegin{}));
  note(check("vertices", largest_vertices()));
  note(check("triangles", largest_triangles()));
  note(check("mesh_end", MeshEnd{}));
  note(check("resend_request", ResendRequest{}));
  note(check("stroke", largest_stroke()));
  note(check("hands", largest_hands()));
  note(check("object", ObjectPose{}));
  note(check("status", StatusReport{}));
  note(check("command", Command{}));
  note(check("workspace", Workspace{}));
  std::printf("LinkMessage    sizeof %5zu, largest body %5zu\n", sizeof(LinkMessage), largest);
  EXPECT_LE(static_cast<double>(sizeof(LinkMessage)), 1.2 * static_cast<double>(largest));
  // Small messages stay small: what the display sends per key, the hands per update.
  EXPECT_LE(sizeof(Command), 2u);
  EXPECT_LE(sizeof(Hands), 68u);
}

}  // namespace
}  // namespace twister::link
