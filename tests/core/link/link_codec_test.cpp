#include "twister/link/link_codec.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace twister::link {
namespace {

template <class M>
std::vector<std::byte> encode(const M& m) {
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
      types.push_back(type_of(**m));
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

void random_live(MessageType type, LinkMessage& m) {
  const auto d = [] {
    return *rc::gen::map(rc::gen::arbitrary<std::int32_t>(),
                         [](std::int32_t v) { return static_cast<double>(v) / 7.0; });
  };
  if (type == MessageType::stroke) {
    StrokeBegin& s = m.emplace<StrokeBegin>();
    s.stroke = *rc::gen::arbitrary<std::uint32_t>();
    s.mesh_version = *rc::gen::arbitrary<std::uint32_t>();
    s.method = static_cast<std::uint8_t>(*rc::gen::inRange(0, 3));
    s.hand_mask = static_cast<std::uint8_t>(*rc::gen::inRange(1, 4));
    s.radius_m = 0.01 + std::abs(d());
    for (std::size_t h = 0; h < kLinkHands; ++h) {
      if ((s.hand_mask & (1u << h)) != 0) s.start[h].origin = {d(), d(), d()};
    }
    // Protocol 5: the segment's symmetry group (none, mirrors, Cn, Cnv).
    const int kind = *rc::gen::inRange(0, 4);
    if (kind == 1) s.symmetry = {1, static_cast<std::uint8_t>(*rc::gen::inRange(1, 8)), 0, 0};
    if (kind >= 2) {
      s.symmetry = {static_cast<std::uint8_t>(kind), 0,
                    static_cast<std::uint8_t>(*rc::gen::inRange(0, 3)),
                    static_cast<std::uint8_t>(*rc::gen::inRange(2, 13))};
    }
  } else if (type == MessageType::hands) {
    Hands& l = m.emplace<Hands>();
    l.sequence = *rc::gen::arbitrary<std::uint16_t>();
    l.stroke = *rc::gen::arbitrary<std::uint16_t>();
    l.flags = static_cast<std::uint8_t>(*rc::gen::inRange(0, 32));
    l.buttons = *rc::gen::arbitrary<std::uint8_t>();
    l.radius_m = 0.25F;
    for (std::size_t h = 0; h < kLinkHands; ++h) {
      if ((l.flags & (kHandSample0 << h)) != 0) l.hands[h] = random_compact();
    }
  } else {
    m.emplace<ObjectPose>().pose = random_compact();
  }
}

float random_float() {
  return *rc::gen::map(rc::gen::inRange(-100000, 100000),
                       [](int v) { return static_cast<float>(v) / 1000.0F; });
}

void random_mesh_message(MessageType type, LinkMessage& m) {
  const auto f = random_float;
  switch (type) {
    case MessageType::mesh_begin:
      m = MeshBegin{*rc::gen::arbitrary<bool>(), *rc::gen::arbitrary<std::uint32_t>(),
                    *rc::gen::arbitrary<std::uint32_t>(), *rc::gen::arbitrary<std::uint32_t>(),
                    *rc::gen::arbitrary<std::uint32_t>()};
      break;
    case MessageType::vertices: {
      Vertices& v = m.emplace<Vertices>();
      v.count = static_cast<std::uint16_t>(*rc::gen::inRange<int>(0, kMaxVerticesPerChunk + 1));
      for (std::size_t i = 0; i < v.count; ++i) {
        v.items[i] = VertexEntry{*rc::gen::arbitrary<std::uint32_t>(), f(), f(), f()};
      }
      break;
    }
    case MessageType::triangles: {
      Triangles& t = m.emplace<Triangles>();
      t.first = *rc::gen::arbitrary<std::uint32_t>();
      t.count = static_cast<std::uint16_t>(*rc::gen::inRange<int>(0, kMaxTrianglesPerChunk + 1));
      for (std::size_t i = 0; i < 3u * t.count; ++i) {
        t.indices[i] = *rc::gen::arbitrary<std::uint32_t>();
      }
      break;
    }
    case MessageType::mesh_end:
      m = MeshEnd{*rc::gen::arbitrary<std::uint32_t>(), *rc::gen::arbitrary<std::uint64_t>()};
      break;
    default:
      m = ResendRequest{*rc::gen::arbitrary<std::uint32_t>(), *rc::gen::arbitrary<std::uint64_t>()};
      break;
  }
}

LinkMessage random_message() {
  LinkMessage m;
  const auto type = static_cast<MessageType>(*rc::gen::inRange<int>(1, kLastMessageType + 1));
  switch (type) {
    case MessageType::hello: {
      Hello& h = m.emplace<Hello>();
      h.role = *rc::gen::element(Role::station, Role::bridge);
      h.flags = static_cast<std::uint8_t>(*rc::gen::inRange(0, kHelloFlagMask + 1));
      h.mesh_version = *rc::gen::arbitrary<std::uint32_t>();
      h.mesh_checksum = *rc::gen::arbitrary<std::uint64_t>();
      h.nonce[3] = *rc::gen::arbitrary<std::uint8_t>();
      break;
    }
    case MessageType::auth:
      m.emplace<Auth>().tag[7] = *rc::gen::arbitrary<std::uint8_t>();
      break;
    case MessageType::bye:
      m = Bye{static_cast<ByeReason>(*rc::gen::inRange(1, kLastByeReason + 1))};
      break;
    case MessageType::mesh_begin:
    case MessageType::vertices:
    case MessageType::triangles:
    case MessageType::mesh_end:
    case MessageType::resend_request:
      random_mesh_message(type, m);
      break;
    case MessageType::stroke:
    case MessageType::hands:
    case MessageType::object:
      random_live(type, m);
      break;
    case MessageType::status: {
      StatusReport& s = m.emplace<StatusReport>();
      s.mesh_version = *rc::gen::arbitrary<std::uint32_t>();
      s.tracker_state = static_cast<std::uint8_t>(*rc::gen::inRange(0, 3));
      s.tracker_rate_hz = random_float();
      s.traffic.live_dropped = *rc::gen::arbitrary<std::uint64_t>();
      s.buttons_state = static_cast<std::uint8_t>(*rc::gen::inRange(0, 2));
      s.strokes.not_saved = *rc::gen::arbitrary<std::uint64_t>();
      // Protocol 7: the next stroke's group and the spectators.
      if (*rc::gen::arbitrary<bool>()) s.symmetry = {2, 0, 1, 6};
      s.spectators = *rc::gen::arbitrary<std::uint8_t>();
      break;
    }
    case MessageType::command:
      m = Command{static_cast<CommandKind>(*rc::gen::inRange(1, kLastCommandKind + 1)),
                  static_cast<std::uint8_t>(*rc::gen::inRange(0, 3))};
      break;
    case MessageType::workspace: {
      Workspace& w = m.emplace<Workspace>();
      w.flags = static_cast<std::uint8_t>(*rc::gen::inRange(0, kWorkspaceFlagMask + 1));
      w.up = {random_float(), random_float(), random_float()};
      w.min = {random_float(), random_float(), random_float()};
      w.max = {random_float(), random_float(), random_float()};
      break;
    }
    case MessageType::visitor: {
      VisitorState& v = m.emplace<VisitorState>();
      v.phase = static_cast<VisitorPhase>(*rc::gen::inRange(0, kLastVisitorPhase + 1));
      v.flags = static_cast<std::uint8_t>(*rc::gen::inRange(0, kVisitorFlagMask + 1));
      v.visitor = *rc::gen::arbitrary<std::uint32_t>();
      v.sculpture = *rc::gen::arbitrary<std::uint32_t>();
      v.strokes = *rc::gen::arbitrary<std::uint32_t>();
      v.idle_left_s = std::abs(random_float());
      v.grace_left_s = std::abs(random_float());
      break;
    }
    case MessageType::notice:
      m = Notice{static_cast<NoticeCode>(*rc::gen::inRange(1, kLastNoticeCode + 1)),
                 *rc::gen::arbitrary<std::uint8_t>()};
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
  RC_ASSERT(type_of(got) == type_of(m));
  RC_ASSERT(encode(got) == bytes);
}

TEST(LinkCodec, DecoderResyncsAfterGarbageAndTornFrames) {
  const MeshEnd a{7, 0x1122334455667788ULL};
  const ResendRequest b{3, 9};
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
  EXPECT_EQ(std::get<ResendRequest>(last).have_version, 3u);
  EXPECT_GE(d.counters().bad_crc + d.counters().bad_cobs, 2u);
}

TEST(LinkCodec, OversizeFrameIsDroppedToTheNextDelimiter) {
  LinkDecoder d;
  std::vector<std::byte> junk(kMaxFrameBytes * 2, std::byte{0x55});
  junk.push_back(std::byte{0});
  const auto fa = encode(Hello{});
  junk.insert(junk.end(), fa.begin(), fa.end());
  EXPECT_EQ(feed(d, junk).size(), 1u);
  EXPECT_EQ(d.counters().oversize, 1u);
}

TEST(LinkCodec, RefusesOtherVersionAndOverCapacityCounts) {
  Vertices m;
  m.count = kMaxVerticesPerChunk + 1;
  std::vector<std::byte> out(kMaxFrameBytes);
  EXPECT_EQ(encode_frame(m, out).status().code(), StatusCode::invalid_argument);
  const std::byte v1[] = {std::byte{1}, std::byte{1}};  // a protocol 1 hello
  LinkMessage got;
  EXPECT_EQ(decode_payload(v1, got).code(), StatusCode::not_supported);
  m.count = 1;
  std::vector<std::byte> tiny(8);
  EXPECT_EQ(encode_frame(m, tiny).status().code(), StatusCode::resource_exhausted);
}

// Protocol 1 sent the screws (605 bytes per two-hand update); protocol 2 derives
// them on the bridge (intent unchanged: a non-finite pose never reaches the shader).
TEST(LinkCodec, NonFiniteOrDegenerateLivePosesAreRefused) {
  Hands m;
  m.flags = kHandSample0 | kHandTracked0 | kStrokeActive;
  m.radius_m = 0.2F;
  m.hands[0].position.y = std::numeric_limits<float>::quiet_NaN();
  LinkDecoder d;
  EXPECT_TRUE(feed(d, encode(m)).empty());
  EXPECT_EQ(d.counters().bad_payload, 1u);
  m.hands[0].position.y = 0.0F;
  m.hands[0].rotation = {0.0F, 0.0F, 0.0F, 0.0F};  // not a rotation
  EXPECT_TRUE(feed(d, encode(m)).empty());
  m.hands[0].rotation = {1.0F, 0.0F, 0.0F, 0.0F};
  EXPECT_EQ(feed(d, encode(m)).size(), 1u);
  StrokeBegin s;
  s.hand_mask = 1;
  s.radius_m = 0.2;
  s.start[0].u.x = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(feed(d, encode(s)).empty());
}

// Protocol 5 (issue 26): a stroke's symmetry group round-trips; a malformed one is
// refused like any out-of-range field.
TEST(LinkCodec, StrokeSymmetryRoundTripsAndMalformedGroupsAreRefused) {
  StrokeBegin s;
  s.hand_mask = 3;
  s.radius_m = 0.2;
  s.symmetry = {3, 0, 1, 6};
  LinkDecoder d;
  LinkMessage got;
  ASSERT_EQ(feed(d, encode(s), &got).size(), 1u);
  EXPECT_EQ(std::get<StrokeBegin>(got).symmetry, s.symmetry);
  const std::array<std::array<std::uint8_t, 4>, 6> bad{
      {{4, 0, 0, 0}, {1, 0, 0, 0}, {1, 8, 0, 0}, {2, 0, 3, 6}, {2, 0, 0, 13}, {0, 0, 0, 2}}};
  for (const auto& b : bad) {
    s.symmetry = b;
    EXPECT_TRUE(feed(d, encode(s)).empty()) << int{b[0]} << " " << int{b[1]};
  }
}

TEST(LinkCodec, CommandsOfUnknownKindOrMethodAreRefused) {
  Command m{CommandKind::set_method, 2};
  auto bytes = encode(m);
  LinkDecoder decoder;
  std::size_t decoded = 0;
  for (const std::byte b : bytes) decoded += decoder.process(b).ok() ? 1 : 0;
  EXPECT_EQ(decoded, 1u);
  for (const Command bad : {Command{static_cast<CommandKind>(0), 0},
                            Command{static_cast<CommandKind>(kLastCommandKind + 1), 0},
                            Command{CommandKind::set_method, 3}}) {
    m = bad;
    bytes = encode(m);
    decoded = 0;
    for (const std::byte b : bytes) decoded += decoder.process(b).ok() ? 1 : 0;
    EXPECT_EQ(decoded, 0u) << static_cast<int>(bad.kind) << " " << int{bad.method};
  }
}

// Protocol 7 (issue 25): the visitor state and the notices round-trip; times that
// are negative or not finite, unknown codes and malformed groups are refused.
TEST(LinkCodec, VisitorNoticeAndStatusOfProtocol7) {
  LinkDecoder d;
  LinkMessage got;
  VisitorState v{VisitorPhase::sculpting, kVisitorResetUndoable, 12, 340, 7, 41.5F, 0.0F};
  ASSERT_EQ(feed(d, encode(v), &got).size(), 1u);
  EXPECT_EQ(std::get<VisitorState>(got).sculpture, 340u);
  EXPECT_EQ(std::get<VisitorState>(got).idle_left_s, 41.5F);
  for (const float bad : {-1.0F, std::numeric_limits<float>::quiet_NaN()}) {
    v.grace_left_s = bad;
    EXPECT_TRUE(feed(d, encode(v)).empty()) << bad;
  }
  for (const auto code : {0, kLastNoticeCode + 1}) {
    EXPECT_TRUE(feed(d, encode(Notice{static_cast<NoticeCode>(code), 0})).empty()) << code;
  }
  ASSERT_EQ(feed(d, encode(Notice{NoticeCode::disk_full, 3}), &got).size(), 1u);
  EXPECT_EQ(std::get<Notice>(got).detail, 3u);
  StatusReport s;
  s.symmetry = {1, 5, 0, 0};
  s.spectators = 2;
  ASSERT_EQ(feed(d, encode(s), &got).size(), 1u);
  EXPECT_EQ(std::get<StatusReport>(got).symmetry, s.symmetry);
  EXPECT_EQ(std::get<StatusReport>(got).spectators, 2u);
  s.symmetry = {1, 0, 0, 0};  // mirrors without a plane: not a group the station sends
  std::vector<std::byte> out(kMaxFrameBytes);
  EXPECT_FALSE(encode_frame(s, out).ok());
}

}  // namespace
}  // namespace twister::link
