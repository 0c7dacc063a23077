// Liberty-family encoder: the hand-written golden frames of liberty_parser_test byte for
// byte, and the round-trip property: random poses of random lists, any model and size
// convention, with noise and truncated frames between them, fed in random splits, parse back
// to the same poses with exact counters.
#include "twister/tracker/liberty_encoder.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "liberty_test_util.hpp"

namespace twister::tracker {
namespace {

using test::hex;
using test::liberty_one_station;
using test::parse_all;
using L = LibertyItem;

std::string encode(const FastrakPose& pose, const LibertyConfig& c,
                   const LibertyFrameExtras& extras = {}) {
  std::array<std::byte, kLibertyMaxFrameBytes> buf{};
  auto n = encode_liberty_frame(pose, c, buf, extras);
  EXPECT_TRUE(n.ok());
  return std::string(reinterpret_cast<const char*>(buf.data()), n.ok() ? *n : 0);
}

TEST(LibertyEncoder, GoldenFrames) {
  FastrakPose p;
  p.station = 1;
  p.position = {1.0f, 2.0f, -1.5f};
  p.quaternion = {0.5f, 0.5f, 0.5f, 0.5f};
  const auto pq = LibertyOutputList::of({L::position, L::quaternion, L::crlf});
  EXPECT_EQ(encode(p, liberty_one_station(LibertyModel::liberty, pq)),
            hex("4C 59 01 43 00 00 1E 00 | 00 00 80 3F  00 00 00 40  00 00 C0 BF |"
                "00 00 00 3F  00 00 00 3F  00 00 00 3F  00 00 00 3F | 0D 0A"));
  LibertyConfig whole = liberty_one_station(LibertyModel::liberty, pq);
  whole.size_field = LibertySizeField::frame;
  EXPECT_EQ(encode(p, whole).substr(6, 2), hex("26 00"));

  FastrakPose q;
  q.station = 2;
  q.position = {0.5f, -1.5f, 2.0f};
  q.euler_deg = {90.0f, 0.0f, 180.0f};
  EXPECT_EQ(encode(q, liberty_one_station(LibertyModel::patriot, LibertyStationConfig{}.list, 2),
                   {kLibertyPoll, 0, 0, 0}),
            hex("50 41 02 50 00 00 1A 00 | 00 00 00 3F  00 00 C0 BF  00 00 00 40 |"
                "00 00 B4 42  00 00 00 00  00 00 34 43 | 0D 0A"));

  FastrakPose r;
  r.station = 1;
  r.position = {2.0f, 0.0f, 0.0f};
  r.quaternion = {1.0f, 0.0f, 0.0f, 0.0f};
  r.button = true;
  EXPECT_EQ(
      encode(r,
             liberty_one_station(LibertyModel::latus,
                                 LibertyOutputList::of({L::position, L::quaternion, L::timestamp,
                                                        L::stylus, L::space})),
             {kLibertyContinuous, 1000, 0, 0}),
      hex("4C 55 01 43 00 00 25 00 | 00 00 00 40  00 00 00 00  00 00 00 00 |"
          "00 00 80 3F  00 00 00 00  00 00 00 00  00 00 00 00 | E8 03 00 00 | 01 00 00 00 | 20"));
}

TEST(LibertyEncoder, Errors) {
  LibertyConfig c = liberty_one_station(LibertyModel::liberty, LibertyStationConfig{}.list);
  FastrakPose p;
  p.station = 2;
  std::array<std::byte, 64> buf{};
  EXPECT_EQ(encode_liberty_frame(p, c, buf).status().code(), StatusCode::invalid_argument);
  p.station = 17;
  EXPECT_EQ(encode_liberty_frame(p, c, buf).status().code(), StatusCode::invalid_argument);
  p.station = 1;
  EXPECT_EQ(encode_liberty_frame(p, c, std::span(buf).first(33)).status().code(),
            StatusCode::resource_exhausted);
  EXPECT_EQ(encode_liberty_frame(p, LibertyConfig{}, buf).status().code(),
            StatusCode::invalid_argument);
}

// --- Round trip ---------------------------------------------------------------------

LibertyOutputList gen_list() {
  LibertyOutputList l;
  l.items[l.count++] = *rc::gen::element(L::position, L::position_ext);
  l.items[l.count++] = *rc::gen::element(L::quaternion, L::euler, L::euler_ext);
  if (*rc::gen::arbitrary<bool>()) l.items[l.count++] = L::timestamp;
  if (*rc::gen::arbitrary<bool>()) l.items[l.count++] = L::stylus;
  if (*rc::gen::arbitrary<bool>()) l.items[l.count++] = L::frame_count;
  l.items[l.count++] = *rc::gen::element(L::space, L::crlf);
  return l;
}

// The pose as the parser reports it for `list`: flags set by the items, values of items
// not in the list left at zero.
FastrakPose as_parsed(const FastrakPose& p, const LibertyOutputList& list) {
  FastrakPose out;
  out.station = p.station;
  out.status = p.status;
  for (std::size_t i = 0; i < list.count; ++i) {
    switch (list.items[i]) {
      case L::position:
      case L::position_ext:
        out.has_position = true;
        out.position = p.position;
        break;
      case L::euler:
      case L::euler_ext:
        out.has.euler = true;
        out.euler_deg = p.euler_deg;
        break;
      case L::quaternion:
        out.has.quaternion = true;
        out.quaternion = p.quaternion;
        break;
      case L::stylus:
        out.has_button = true;
        out.button = p.button;
        break;
      default:
        break;
    }
  }
  return out;
}

FastrakPose gen_pose(std::uint8_t station, Units units) {
  FastrakPose p;
  p.station = station;
  p.status = *rc::gen::element(' ', ' ', 'A', 'B');
  const double lim = units == Units::inches ? 399.0 : 1015.0;
  for (float& v : p.position) {
    v = static_cast<float>(*rc::gen::inRange(-1000000, 1000001) * lim / 1e6);
  }
  p.euler_deg = {static_cast<float>(*rc::gen::inRange(-179000, 179001) / 1000.0),
                 static_cast<float>(*rc::gen::inRange(-89000, 89001) / 1000.0),
                 static_cast<float>(*rc::gen::inRange(-179000, 179001) / 1000.0)};
  double q[4];
  double n2 = 0.0;
  do {
    n2 = 0.0;
    for (double& x : q) {
      x = *rc::gen::inRange(-10000, 10001) / 10000.0;
      n2 += x * x;
    }
  } while (n2 < 0.01);
  for (int i = 0; i < 4; ++i)
    p.quaternion[static_cast<std::size_t>(i)] = static_cast<float>(q[i] / std::sqrt(n2));
  p.button = *rc::gen::arbitrary<bool>();
  return p;
}

RC_GTEST_PROP(LibertyRoundTrip, NoiseAndTruncatedFramesAreSkippedAndCounted, ()) {
  LibertyConfig c;
  c.model = *rc::gen::element(LibertyModel::liberty, LibertyModel::patriot, LibertyModel::latus);
  c.units = *rc::gen::element(Units::inches, Units::centimetres);
  c.size_field = *rc::gen::element(LibertySizeField::body, LibertySizeField::frame);
  const int stations = *rc::gen::inRange(1, 4);
  std::vector<std::uint8_t> ids;
  for (int i = 0; i < stations; ++i) {
    const auto s = static_cast<std::uint8_t>(*rc::gen::inRange(1, kLibertyMaxStations + 1));
    c.stations[s - 1u] = {true, gen_list()};
    ids.push_back(s);
  }
  const auto tag = frame_tag(c.model);
  // Noise bytes: anything that cannot begin a frame of any model.
  const auto noise_byte =
      rc::gen::suchThat(rc::gen::arbitrary<char>(), [](char b) { return b != 'L' && b != 'P'; });
  const int count = *rc::gen::inRange(1, 30);
  std::string stream;
  std::vector<FastrakPose> want;
  std::uint64_t dropped = 0, truncated = 0, runs = 0;
  for (int i = 0; i < count; ++i) {
    const FastrakPose p = gen_pose(*rc::gen::elementOf(ids), c.units);
    const std::string frame =
        encode(p, c, {kLibertyContinuous, static_cast<std::uint32_t>(i), 0, 0});
    std::string gap;
    if (*rc::gen::inRange(0, 3) == 0) {
      gap += *rc::gen::container<std::string>(*rc::gen::inRange(0, 12), noise_byte);
    }
    if (*rc::gen::inRange(0, 4) == 0) {
      // A frame cut inside its header (2..7 bytes): a body cut short could take the next
      // frame's bytes for its own, which only a checksum could tell.
      gap += frame.substr(0, *rc::gen::inRange<std::size_t>(2, kLibertyHeaderBytes));
      ++truncated;
    }
    if (!gap.empty()) ++runs;
    dropped += gap.size();
    stream += gap + frame;
    want.push_back(as_parsed(p, c.stations[p.station - 1u].list));
  }
  (void)tag;
  const auto chunks =
      *rc::gen::container<std::vector<std::size_t>>(rc::gen::inRange<std::size_t>(1, 60));
  LibertyParser parser(c);
  const auto ev = parse_all(parser, stream, chunks);
  std::vector<FastrakPose> got;
  for (const auto& e : ev) {
    RC_ASSERT(e.kind != EventKind::error);
    if (e.kind == EventKind::pose) got.push_back(e.pose);
  }
  RC_ASSERT(got == want);
  const auto& k = parser.counters();
  RC_ASSERT(k.poses == static_cast<std::uint64_t>(count));
  RC_ASSERT(k.bytes == stream.size());
  RC_ASSERT(k.dropped_bytes == dropped);
  RC_ASSERT(k.bad_frames == truncated);
  RC_ASSERT(k.resyncs == runs);
  RC_ASSERT(k.oversize <= truncated);
}

}  // namespace
}  // namespace twister::tracker
