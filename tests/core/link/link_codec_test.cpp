#include "twister/link/link_codec.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdio>
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

CompactPose random_compact() {
  const auto f = [] {
    return *rc::gen::map(rc::gen::inRange(-100000, 100000),
                         [](int v) { return static_cast<float>(v) / 1000.0F; });
  };
  CompactPose p;
  p.position = {f(), f(), f()};
  p.rotation = {0.5F, 0.5F, -0.5F, *rc::gen::element(0.5F, -0.5F)};
  return p;
}

void random_live(LinkMessage& m) {
  const auto d = [] {
    return *rc::gen::map(rc::gen::arbitrary<std::int32_t>(),
                         [](std::int32_t v) { return static_cast<double>(v) / 7.0; });
  };
  if (m.type == MessageType::stroke) {
    StrokeBegin& s = m.stroke;
    s.stroke = *rc::gen::arbitrary<std::uint32_t>();
    s.mesh_version = *rc::gen::arbitrary<std::uint32_t>();
    s.method = static_cast<std::uint8_t>(*rc::gen::inRange(0, 3));
    s.hand_mask = static_cast<std::uint8_t>(*rc::gen::inRange(1, 4));
    s.radius_m = 0.01 + std::abs(d());
    for (std::size_t h = 0; h < kLinkHands; ++h) {
      if ((s.hand_mask & (1u << h)) != 0) s.start[h].origin = {d(), d(), d()};
    }
  } else if (m.type == MessageType::hands) {
    Hands& l = m.hands;
    l.sequence = *rc::gen::arbitrary<std::uint16_t>();
    l.stroke = *rc::gen::arbitrary<std::uint16_t>();
    l.flags = static_cast<std::uint8_t>(*rc::gen::inRange(0, 32));
    l.buttons = *rc::gen::arbitrary<std::uint8_t>();
    l.radius_m = 0.25F;
    for (std::size_t h = 0; h < kLinkHands; ++h) {
      if ((l.flags & (kHandSample0 << h)) != 0) l.hands[h] = random_compact();
    }
  } else {
    m.object.pose = random_compact();
  }
}

LinkMessage random_message() {
  LinkMessage m;
  const auto type = *rc::gen::inRange<int>(1, kLastMessageType + 1);
  m.type = static_cast<MessageType>(type);
  const auto f = [] {
    return *rc::gen::map(rc::gen::inRange(-100000, 100000),
                         [](int v) { return static_cast<float>(v) / 1000.0F; });
  };
  switch (m.type) {
    case MessageType::hello:
      m.hello.role = *rc::gen::element(Role::station, Role::bridge);
      m.hello.flags = static_cast<std::uint8_t>(*rc::gen::inRange(0, 2));
      m.hello.mesh_version = *rc::gen::arbitrary<std::uint32_t>();
      m.hello.mesh_checksum = *rc::gen::arbitrary<std::uint64_t>();
      m.hello.nonce[3] = *rc::gen::arbitrary<std::uint8_t>();
      break;
    case MessageType::auth:
      m.auth.tag[7] = *rc::gen::arbitrary<std::uint8_t>();
      break;
    case MessageType::bye:
      m.bye.reason = static_cast<ByeReason>(*rc::gen::inRange(1, kLastByeReason + 1));
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
    case MessageType::resend_request:
      m.resend_request =
          ResendRequest{*rc::gen::arbitrary<std::uint32_t>(), *rc::gen::arbitrary<std::uint64_t>()};
      break;
    case MessageType::stroke:
    case MessageType::hands:
    case MessageType::object:
      random_live(m);
      break;
    case MessageType::status:
      m.status.mesh_version = *rc::gen::arbitrary<std::uint32_t>();
      m.status.tracker_state = static_cast<std::uint8_t>(*rc::gen::inRange(0, 3));
      m.status.tracker_rate_hz = f();
      m.status.live_dropped = *rc::gen::arbitrary<std::uint64_t>();
      m.status.strokes_not_saved = *rc::gen::arbitrary<std::uint64_t>();
      break;
    case MessageType::command:
      m.command.kind = static_cast<CommandKind>(*rc::gen::inRange(1, kLastCommandKind + 1));
      m.command.method = static_cast<std::uint8_t>(*rc::gen::inRange(0, 3));
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
  const std::byte v1[] = {std::byte{1}, std::byte{1}};  // a protocol 1 hello
  LinkMessage got;
  EXPECT_EQ(decode_payload(v1, got).code(), StatusCode::not_supported);
  m.vertices.count = 1;
  std::vector<std::byte> tiny(8);
  EXPECT_EQ(encode_frame(m, tiny).status().code(), StatusCode::resource_exhausted);
}

// Protocol 1 sent the screws (605 bytes per two-hand update); protocol 2 derives
// them on the bridge (intent unchanged: a non-finite pose never reaches the shader).
TEST(LinkCodec, NonFiniteOrDegenerateLivePosesAreRefused) {
  LinkMessage m;
  m.type = MessageType::hands;
  m.hands.flags = kHandSample0 | kHandTracked0 | kStrokeActive;
  m.hands.radius_m = 0.2F;
  m.hands.hands[0].position.y = std::numeric_limits<float>::quiet_NaN();
  LinkDecoder d;
  EXPECT_TRUE(feed(d, encode(m)).empty());
  EXPECT_EQ(d.counters().bad_payload, 1u);
  m.hands.hands[0].position.y = 0.0F;
  m.hands.hands[0].rotation = {0.0F, 0.0F, 0.0F, 0.0F};  // not a rotation
  EXPECT_TRUE(feed(d, encode(m)).empty());
  m.hands.hands[0].rotation = {1.0F, 0.0F, 0.0F, 0.0F};
  EXPECT_EQ(feed(d, encode(m)).size(), 1u);
  LinkMessage s;
  s.type = MessageType::stroke;
  s.stroke.hand_mask = 1;
  s.stroke.radius_m = 0.2;
  s.stroke.start[0].u.x = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(feed(d, encode(s)).empty());
}

TEST(LinkCodec, CommandsOfUnknownKindOrMethodAreRefused) {
  LinkMessage m;
  m.type = MessageType::command;
  m.command = Command{CommandKind::set_method, 2};
  auto bytes = encode(m);
  LinkDecoder decoder;
  std::size_t decoded = 0;
  for (const std::byte b : bytes) decoded += decoder.process(b).ok() ? 1 : 0;
  EXPECT_EQ(decoded, 1u);
  for (const Command bad : {Command{static_cast<CommandKind>(0), 0},
                            Command{static_cast<CommandKind>(kLastCommandKind + 1), 0},
                            Command{CommandKind::set_method, 3}}) {
    m.command = bad;
    bytes = encode(m);
    decoded = 0;
    for (const std::byte b : bytes) decoded += decoder.process(b).ok() ? 1 : 0;
    EXPECT_EQ(decoded, 0u) << static_cast<int>(bad.kind) << " " << int{bad.method};
  }
}

}  // namespace
}  // namespace twister::link
