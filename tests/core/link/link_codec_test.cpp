#include "twister/link/link_codec.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <limits>
#include <vector>

namespace twister::link {
namespace {

std::vector<std::byte> encode(const LinkMessage& m) {
  std::vector<std::byte> out(kMaxFrameBytes);
  const auto n = encode_frame(m, out);
  EXPECT_TRUE(n.ok());
  out.resize(n.ok() ? *n : 0);
  return out;
}

// Feeds bytes; returns the decoded messages' types and keeps the last message.
std::vector<MessageType> feed(LinkDecoder& d, const std::vector<std::byte>& bytes,
                              LinkMessage* last = nullptr) {
  std::vector<MessageType> types;
  for (const std::byte b : bytes) {
    if (const auto m = d.process(b); m.ok()) {
      types.push_back((*m)->type);
      if (last != nullptr) *last = **m;
    }
  }
  return types;
}

LinkMessage random_message() {
  LinkMessage m;
  const auto type = *rc::gen::inRange<int>(1, 9);
  m.type = static_cast<MessageType>(type);
  const auto f = [] {
    return *rc::gen::map(rc::gen::inRange(-100000, 100000),
                         [](int v) { return static_cast<float>(v) / 1000.0F; });
  };
  const auto d = [] {
    return *rc::gen::map(rc::gen::arbitrary<std::int32_t>(),
                         [](std::int32_t v) { return static_cast<double>(v) / 7.0; });
  };
  switch (m.type) {
    case MessageType::hello:
      m.hello = Hello{*rc::gen::element(Role::station, Role::bridge),
                      *rc::gen::arbitrary<std::uint32_t>(), *rc::gen::arbitrary<std::uint64_t>()};
      break;
    case MessageType::mesh_begin:
      m.mesh_begin =
          MeshBegin{*rc::gen::arbitrary<bool>(), *rc::gen::arbitrary<std::uint32_t>(),
                    *rc::gen::arbitrary<std::uint32_t>(), *rc::gen::arbitrary<std::uint32_t>(),
                    *rc::gen::arbitrary<std::uint32_t>()};
      break;
    case MessageType::vertices:
      m.vertices.count =
          static_cast<std::uint16_t>(*rc::gen::inRange<int>(0, kMaxVerticesPerChunk + 1));
      for (std::size_t i = 0; i < m.vertices.count; ++i) {
        m.vertices.items[i] = VertexEntry{*rc::gen::arbitrary<std::uint32_t>(), f(), f(), f()};
      }
      break;
    case MessageType::triangles:
      m.triangles.first = *rc::gen::arbitrary<std::uint32_t>();
      m.triangles.count =
          static_cast<std::uint16_t>(*rc::gen::inRange<int>(0, kMaxTrianglesPerChunk + 1));
      for (std::size_t i = 0; i < 3u * m.triangles.count; ++i) {
        m.triangles.indices[i] = *rc::gen::arbitrary<std::uint32_t>();
      }
      break;
    case MessageType::mesh_end:
      m.mesh_end =
          MeshEnd{*rc::gen::arbitrary<std::uint32_t>(), *rc::gen::arbitrary<std::uint64_t>()};
      break;
    case MessageType::live_warp: {
      LiveWarp& l = m.live_warp;
      l.mesh_version = *rc::gen::arbitrary<std::uint32_t>();
      l.stroke = *rc::gen::arbitrary<std::uint32_t>();
      l.active = *rc::gen::arbitrary<bool>();
      l.method = static_cast<std::uint8_t>(*rc::gen::inRange(0, 3));
      l.hand_mask = static_cast<std::uint8_t>(*rc::gen::inRange(0, 4));
      l.radius_m = d();
      for (std::size_t h = 0; h < kLinkHands; ++h) {
        if ((l.hand_mask & (1u << h)) == 0) continue;
        LiveHand& hand = l.hands[h];
        hand.start.origin = {d(), d(), d()};
        hand.end.u = {d(), d(), d()};
        hand.screw.axis = {d(), d(), d()};
        hand.screw.angle = d();
        hand.screw.cot_half = d();
        hand.screw.pure_translation = *rc::gen::arbitrary<bool>();
      }
      break;
    }
    case MessageType::resend_request:
      m.resend_request =
          ResendRequest{*rc::gen::arbitrary<std::uint32_t>(), *rc::gen::arbitrary<std::uint64_t>()};
      break;
    case MessageType::status:
      m.status.mesh_version = *rc::gen::arbitrary<std::uint32_t>();
      m.status.live_dropped = *rc::gen::arbitrary<std::uint64_t>();
      m.status.frames_rejected = *rc::gen::arbitrary<std::uint64_t>();
      break;
  }
  return m;
}

// Re-encoding the decoded message must give the same bytes: every field survived.
RC_GTEST_PROP(LinkCodec, RoundTripIsByteExactForAnySplit, ()) {
  const LinkMessage m = random_message();
  const auto bytes = encode(m);
  RC_ASSERT(!bytes.empty());
  RC_ASSERT(bytes.back() == std::byte{0});
  for (std::size_t i = 0; i + 1 < bytes.size(); ++i) RC_ASSERT(bytes[i] != std::byte{0});
  LinkDecoder decoder;
  LinkMessage got;
  const auto types = feed(decoder, bytes, &got);
  RC_ASSERT(types.size() == 1u);
  RC_ASSERT(got.type == m.type);
  RC_ASSERT(encode(got) == bytes);
}

TEST(LinkCodec, DecoderResyncsAfterGarbageAndTornFrames) {
  LinkMessage a;
  a.type = MessageType::mesh_end;
  a.mesh_end = MeshEnd{7, 0x1122334455667788ULL};
  LinkMessage b;
  b.type = MessageType::resend_request;
  b.resend_request = ResendRequest{3, 9};
  const auto fa = encode(a);
  const auto fb = encode(b);
  std::vector<std::byte> stream;
  for (int i = 1; i < 300; ++i)
    stream.push_back(static_cast<std::byte>(i * 37 % 255 + 1));  // garbage, no 0
  stream.push_back(std::byte{0});
  stream.insert(stream.end(), fa.begin(), fa.begin() + 5);  // torn frame...
  stream.insert(stream.end(), fb.begin(), fb.end());        // ...swallowed with b's start
  stream.insert(stream.end(), fa.begin(), fa.end());
  auto corrupt = fb;
  corrupt[3] ^= std::byte{0x40};
  stream.insert(stream.end(), corrupt.begin(), corrupt.end());
  stream.insert(stream.end(), fb.begin(), fb.end());
  LinkDecoder d;
  LinkMessage last;
  const auto types = feed(d, stream, &last);
  ASSERT_EQ(types.size(), 2u);
  EXPECT_EQ(types[0], MessageType::mesh_end);
  EXPECT_EQ(types[1], MessageType::resend_request);
  EXPECT_EQ(last.resend_request.have_version, 3u);
  EXPECT_GE(d.counters().bad_crc + d.counters().bad_cobs, 2u);
}

TEST(LinkCodec, OversizeFrameIsDroppedToTheNextDelimiter) {
  LinkDecoder d;
  std::vector<std::byte> junk(kMaxFrameBytes * 2, std::byte{0x55});
  junk.push_back(std::byte{0});
  LinkMessage a;
  a.type = MessageType::hello;
  const auto fa = encode(a);
  junk.insert(junk.end(), fa.begin(), fa.end());
  EXPECT_EQ(feed(d, junk).size(), 1u);
  EXPECT_EQ(d.counters().oversize, 1u);
}

TEST(LinkCodec, RefusesOtherVersionAndOverCapacityCounts) {
  LinkMessage m;
  m.type = MessageType::vertices;
  m.vertices.count = kMaxVerticesPerChunk + 1;
  std::vector<std::byte> out(kMaxFrameBytes);
  EXPECT_EQ(encode_frame(m, out).status().code(), StatusCode::invalid_argument);
  const std::byte v2[] = {std::byte{2}, std::byte{1}};
  LinkMessage got;
  EXPECT_EQ(decode_payload(v2, got).code(), StatusCode::not_supported);
  m.vertices.count = 1;
  std::vector<std::byte> tiny(8);
  EXPECT_EQ(encode_frame(m, tiny).status().code(), StatusCode::resource_exhausted);
}

TEST(LinkCodec, NonFiniteLiveWarpIsRefused) {
  LinkMessage m;
  m.type = MessageType::live_warp;
  m.live_warp.active = true;
  m.live_warp.hand_mask = 1;
  m.live_warp.radius_m = 0.2;
  m.live_warp.hands[0].screw.mid.y = std::numeric_limits<double>::quiet_NaN();
  LinkDecoder d;
  EXPECT_TRUE(feed(d, encode(m)).empty());
  EXPECT_EQ(d.counters().bad_payload, 1u);
  m.live_warp.hands[0].screw.mid.y = 0.0;
  m.live_warp.hands[0].end.origin.x = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(feed(d, encode(m)).empty());
  m.live_warp.hands[0].end.origin.x = 0.0;
  EXPECT_EQ(feed(d, encode(m)).size(), 1u);
}

}  // namespace
}  // namespace twister::link
