// Encoder: the layouts of docs/fastrak-protocol.md §3 byte for byte, and the round-trip
// property: any sequence of valid records, encoded in either format and fed in arbitrary
// splits, decodes to the same records.
#include "twister/tracker/fastrak_encoder.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "tracker_test_util.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::tracker {
namespace {

using test::bytes_of;
using test::parse_all;

std::string encode(const FastrakPose& pose, const FastrakConfig& c) {
  std::array<std::byte, 512> buf{};
  auto n = encode_record(pose, c, buf);
  EXPECT_TRUE(n.ok());
  return std::string(reinterpret_cast<const char*>(buf.data()), n.ok() ? *n : 0);
}

TEST(FastrakEncoder, DefaultAsciiRecordMatchesSpecLayout) {
  FastrakConfig c =
      test::one_station(Format::ascii, OutputList::of({Item::position, Item::euler, Item::crlf}));
  FastrakPose p;
  p.station = 1;
  p.position = {12.5f, -3.21f, -123.45f};
  p.euler_deg = {90.0f, 0.0f, 180.0f};
  EXPECT_EQ(encode(p, c), std::string("01 ") + "  12.50" + "  -3.21" + "-123.45" + "  90.00" +
                              "   0.00" + " 180.00" + "\r\n");
}

TEST(FastrakEncoder, ExtendedAndBinaryLayouts) {
  FastrakConfig c =
      test::one_station(Format::ascii, OutputList::of({Item::position_ext, Item::space}));
  FastrakPose p;
  p.station = 1;
  p.position = {12.345f, -0.5f, 0.0f};
  EXPECT_EQ(encode(p, c), "01  1.23450E+01 -5.00000E-01  0.00000E+00  ");
  c.format = Format::binary;
  c.stations[0].list = OutputList::of({Item::position, Item::stylus, Item::crlf});
  p.button = true;
  EXPECT_EQ(encode(p, c),
            "01 " + test::f32le(12.345f) + test::f32le(-0.5f) + test::f32le(0.0f) + " 1\r\n");
}

TEST(FastrakEncoder, StatusReplyIs55BytesAndParses) {
  std::array<std::byte, 64> buf{};
  FastrakStatus s;
  s.station = 1;
  s.flags = 0x3F0;
  s.binary = true;
  s.continuous = true;
  auto n = encode_status(s, buf);
  ASSERT_TRUE(n.ok());
  ASSERT_EQ(*n, 55u);
  FastrakParser parser(
      test::one_station(Format::binary, OutputList::of({Item::position, Item::crlf})));
  auto ev = parse_all(parser, std::string(reinterpret_cast<const char*>(buf.data()), *n));
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::status);
  EXPECT_EQ(ev[0].status.flags, 0x3F9);
  EXPECT_TRUE(ev[0].status.binary);
  EXPECT_TRUE(ev[0].status.continuous);
  EXPECT_FALSE(ev[0].status.centimetres);
}

TEST(FastrakEncoder, ErrorsForBadStationAndSmallBuffer) {
  FastrakConfig c = test::one_station(Format::ascii, OutputList::of({Item::position, Item::crlf}));
  FastrakPose p;
  p.station = 2;
  std::array<std::byte, 64> buf{};
  EXPECT_EQ(encode_record(p, c, buf).status().code(), StatusCode::invalid_argument);
  p.station = 1;
  EXPECT_EQ(encode_record(p, c, std::span(buf).first(10)).status().code(),
            StatusCode::resource_exhausted);
}

// --- round-trip property -------------------------------------------------------

// Values on the ASCII grid (2 or 4 decimals) so that ASCII decoding is exact.
float grid(double v, int decimals) {
  const double s = decimals == 2 ? 100.0 : 10000.0;
  return static_cast<float>(static_cast<double>(std::llround(v * s)) / s);
}

FastrakConfig gen_config(bool packed16 = false) {
  FastrakConfig c;
  c.format = packed16 ? Format::binary16 : *rc::gen::element(Format::ascii, Format::binary);
  c.units = *rc::gen::element(Units::inches, Units::centimetres);
  c.ascii_stylus_width = *rc::gen::element<std::uint8_t>(1, 2);
  const int n = *rc::gen::inRange(1, 5);
  for (int s = 0; s < n; ++s) {
    ReceiverConfig& st = c.stations[static_cast<std::size_t>(s)];
    st.enabled = true;
    OutputList l;
    l.items[l.count++] = Item::position;
    const Item o = *rc::gen::element(Item::euler, Item::quaternion, Item::dcm_x);
    if (o == Item::dcm_x) {
      l.items[l.count++] = Item::dcm_x;
      l.items[l.count++] = Item::dcm_y;
      l.items[l.count++] = Item::dcm_z;
    } else {
      l.items[l.count++] = o;
    }
    if (*rc::gen::arbitrary<bool>()) l.items[l.count++] = Item::stylus;
    l.items[l.count++] = *rc::gen::element(Item::space, Item::crlf);
    st.list = l;
  }
  return c;
}

FastrakPose gen_pose(const FastrakConfig& c) {
  int n = 0;
  while (n < kMaxStations && c.stations[static_cast<std::size_t>(n)].enabled) ++n;
  FastrakPose p;
  p.station = static_cast<std::uint8_t>(*rc::gen::inRange(1, n + 1));
  p.status = *rc::gen::element(' ', ' ', 'y', 'B');
  const OutputList& l = c.stations[p.station - 1u].list;
  const bool inches = c.units == Units::inches;
  const double lim = c.format == Format::binary16 ? (inches ? 65.0 : 166.0)
                     : inches                     ? 399.0
                                                  : 999.0;
  for (float& v : p.position) v = grid(*rc::gen::inRange(-1000000, 1000001) * lim / 1e6, 2);
  p.has_position = true;
  // A random rotation through a random unit quaternion.
  std::array<double, 4> q{};
  double norm = 0;
  do {
    for (double& x : q) x = *rc::gen::inRange(-10000, 10001) / 10000.0;
    norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  } while (norm < 0.1);
  for (double& x : q) x /= norm;
  std::array<float, 4> qf{};
  for (std::size_t i = 0; i < 4; ++i) qf[i] = grid(q[i], 4);
  const bool ascii = c.format == Format::ascii;
  for (std::size_t i = 0; i < l.count; ++i) {
    switch (l.items[i]) {
      case Item::euler: {
        p.has.euler = true;
        const glm::dvec3 e = euler_deg_from_rotation(*rotation_from_quaternion(qf));
        for (int k = 0; k < 3; ++k) p.euler_deg[static_cast<std::size_t>(k)] = grid(e[k], 2);
        p.euler_deg[1] = std::fmax(-90.0f, std::fmin(90.0f, p.euler_deg[1]));
        break;
      }
      case Item::quaternion:
        p.has.quaternion = true;
        p.quaternion =
            ascii ? qf
                  : std::array<float, 4>{static_cast<float>(q[0]), static_cast<float>(q[1]),
                                         static_cast<float>(q[2]), static_cast<float>(q[3])};
        break;
      case Item::dcm_x: {
        p.has.dcm = true;
        const glm::dmat3 r = *rotation_from_quaternion(qf);
        for (int row = 0; row < 3; ++row) {
          for (int col = 0; col < 3; ++col) {
            const double v = r[col][row];
            p.dcm[static_cast<std::size_t>(3 * row + col)] =
                ascii ? grid(v, 4) : static_cast<float>(v);
          }
        }
        break;
      }
      case Item::stylus:
        p.has_button = true;
        p.button = *rc::gen::arbitrary<bool>();
        break;
      default:
        break;
    }
  }
  return p;
}

RC_GTEST_PROP(FastrakRoundTrip, AnyRecordsAnySplitDecodeToTheSameRecords, ()) {
  const FastrakConfig c = gen_config();
  const int count = *rc::gen::inRange(1, 40);
  std::vector<FastrakPose> poses;
  std::string stream;
  for (int i = 0; i < count; ++i) {
    poses.push_back(gen_pose(c));
    stream += encode(poses.back(), c);
  }
  std::vector<std::size_t> splits =
      *rc::gen::container<std::vector<std::size_t>>(rc::gen::inRange<std::size_t>(1, 80));
  FastrakParser parser(c);
  auto events = parse_all(parser, stream, splits);
  RC_ASSERT(events.size() == poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    RC_ASSERT(events[i].kind == EventKind::pose);
    RC_ASSERT(static_cast<bool>(events[i].pose == poses[i]));
  }
  RC_ASSERT(parser.counters().dropped_bytes == 0u);
}

// With noise between records, every record still decodes, and each noise run is one
// resync (noise bytes here can never start a record or reply).
RC_GTEST_PROP(FastrakRoundTrip, NoiseBetweenRecordsCostsOneResyncPerRun, ()) {
  const FastrakConfig c = gen_config();
  const int count = *rc::gen::inRange(1, 20);
  std::string stream;
  int runs = 0;
  for (int i = 0; i < count; ++i) {
    const int noise = *rc::gen::inRange(0, 20);
    if (noise > 0) {
      ++runs;
      for (int k = 0; k < noise; ++k) stream += *rc::gen::element('x', '\r', '\n', '9', '\x7f');
    }
    stream += encode(gen_pose(c), c);
  }
  FastrakParser parser(c);
  auto events = parse_all(
      parser, stream,
      *rc::gen::container<std::vector<std::size_t>>(rc::gen::inRange<std::size_t>(1, 50)));
  int poses = 0, resyncs = 0;
  for (const auto& e : events) {
    poses += e.kind == EventKind::pose;
    resyncs += e.kind == EventKind::resync;
  }
  RC_ASSERT(poses == count);
  RC_ASSERT(resyncs == runs);
}

// Extended-precision items (52, 54, 55-57, 61): records decode, and re-encoding the
// decoded records gives back the same bytes, whatever the split.
RC_GTEST_PROP(FastrakRoundTrip, ExtendedItemsRoundTripByteForByte, ()) {
  FastrakConfig c = test::one_station(
      *rc::gen::element(Format::ascii, Format::binary),
      OutputList::of({Item::position_ext, Item::euler_ext, Item::dcm_x_ext, Item::dcm_y_ext,
                      Item::dcm_z_ext, Item::quaternion_ext, Item::stylus_ext, Item::crlf}));
  const int count = *rc::gen::inRange(1, 15);
  std::string stream;
  for (int i = 0; i < count; ++i) {
    FastrakPose p;
    p.station = 1;
    for (float& v : p.position)
      v = static_cast<float>(*rc::gen::inRange(-399000, 399001)) / 1000.0f;
    const double az = *rc::gen::inRange(-179, 180), el = *rc::gen::inRange(-89, 90),
                 roll = *rc::gen::inRange(-179, 180);
    p.euler_deg = {static_cast<float>(az), static_cast<float>(el), static_cast<float>(roll)};
    const glm::dmat3 r = rotation_from_euler_deg(az, el, roll);
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col)
        p.dcm[static_cast<std::size_t>(3 * row + col)] = static_cast<float>(r[col][row]);
    p.quaternion = {1.0f, 0.0f, 0.0f, 0.0f};
    p.button = *rc::gen::arbitrary<bool>();
    stream += encode(p, c);
  }
  FastrakParser parser(c);
  auto events = parse_all(
      parser, stream,
      *rc::gen::container<std::vector<std::size_t>>(rc::gen::inRange<std::size_t>(1, 90)));
  RC_ASSERT(events.size() == static_cast<std::size_t>(count));
  std::string again;
  for (const auto& e : events) {
    RC_ASSERT(e.kind == EventKind::pose);
    again += encode(e.pose, c);
  }
  RC_ASSERT(again == stream);
}

// 16-bit packed records (docs/fastrak-protocol.md §3.4): any records in any split decode
// to the sent values within one count, and re-encoding a decoded record gives back its
// bytes.
RC_GTEST_PROP(FastrakRoundTrip, Packed16RecordsDecodeWithinOneCountAndReencodeExactly, ()) {
  const FastrakConfig c = gen_config(true);
  const int count = *rc::gen::inRange(1, 40);
  std::vector<FastrakPose> poses;
  std::vector<std::string> records;
  std::string stream;
  for (int i = 0; i < count; ++i) {
    poses.push_back(gen_pose(c));
    records.push_back(encode(poses.back(), c));
    stream += records.back();
  }
  FastrakParser parser(c);
  auto events = parse_all(
      parser, stream,
      *rc::gen::container<std::vector<std::size_t>>(rc::gen::inRange<std::size_t>(1, 60)));
  RC_ASSERT(events.size() == poses.size());
  const double pos_count = (c.units == Units::inches ? 65.48 : 166.32) / 32768.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    RC_ASSERT(events[i].kind == EventKind::pose);
    const FastrakPose& got = events[i].pose;
    const FastrakPose& sent = poses[i];
    RC_ASSERT(got.station == sent.station && got.status == sent.status);
    RC_ASSERT(got.button == sent.button && got.has == sent.has);
    for (std::size_t k = 0; k < 3; ++k) {
      RC_ASSERT(std::fabs(got.position[k] - sent.position[k]) <= pos_count);
      RC_ASSERT(std::fabs(got.euler_deg[k] - sent.euler_deg[k]) <= 180.0 / 32768.0 + 1e-6);
    }
    for (std::size_t k = 0; k < 9; ++k) RC_ASSERT(std::fabs(got.dcm[k] - sent.dcm[k]) <= 1e-4);
    for (std::size_t k = 0; k < 4; ++k) {
      RC_ASSERT(std::fabs(got.quaternion[k] - sent.quaternion[k]) <= 1e-4);
    }
    RC_ASSERT(encode(got, c) == records[i]);
  }
  RC_ASSERT(parser.counters().dropped_bytes == 0u);
}

}  // namespace
}  // namespace twister::tracker
