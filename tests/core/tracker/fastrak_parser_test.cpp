// FastrakParser against byte streams written from the spec (§3.2, §3.3, §3.6, §3.7,
// §3.8, §5): record layouts, replies, and every documented fault case.
#include "twister/tracker/fastrak_parser.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "allocation_counter.hpp"
#include "tracker_test_util.hpp"

namespace twister::tracker {
namespace {

using test::bytes_of;
using test::f32le;
using test::one_station;
using test::parse_all;

const OutputList kDefaultList = OutputList::of({Item::position, Item::euler, Item::crlf});

// "01 " + x y z + az el roll + CR LF, 47 bytes (§3.2 the manual's own figure).
const std::string kDefaultAscii = std::string("01 ") + "  12.50" + "  -3.21" + "-123.45" +
                                  "  90.00" + "   0.00" + " 180.00" + "\r\n";

TEST(FastrakParser, RecordLengthsMatchSpecTables) {
  EXPECT_EQ(record_length(kDefaultList, Format::ascii), 47u);
  EXPECT_EQ(
      record_length(OutputList::of({Item::position, Item::quaternion, Item::crlf}), Format::ascii),
      54u);
  EXPECT_EQ(record_length(
                OutputList::of({Item::position, Item::dcm_x, Item::dcm_y, Item::dcm_z, Item::crlf}),
                Format::ascii),
            89u);
  EXPECT_EQ(record_length(OutputList::of({Item::position, Item::quaternion, Item::space}),
                          Format::binary),
            32u);
  EXPECT_EQ(
      record_length(OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::space}),
                    Format::binary),
      34u);
  EXPECT_EQ(record_length(OutputList::of({Item::position, Item::euler, Item::stylus, Item::crlf}),
                          Format::binary),
            31u);
  EXPECT_EQ(record_length(kDefaultList, Format::binary), 29u);
  // The spec's table says 41 (= 3 + 36 + 2) for 2,5,6,7,1, which leaves out the 12
  // position bytes; 41 is the length of 5,6,7,1 and 2,5,6,7,1 is 53 (docs/fastrak.md).
  EXPECT_EQ(record_length(OutputList::of({Item::dcm_x, Item::dcm_y, Item::dcm_z, Item::crlf}),
                          Format::binary),
            41u);
  EXPECT_EQ(record_length(
                OutputList::of({Item::position, Item::dcm_x, Item::dcm_y, Item::dcm_z, Item::crlf}),
                Format::binary),
            53u);
  EXPECT_EQ(
      record_length(OutputList::of({Item::position, Item::quaternion, Item::crlf}), Format::binary),
      33u);
  EXPECT_EQ(record_length(OutputList::of({Item::position_ext, Item::crlf}), Format::ascii),
            3u + 39u + 2u);
}

TEST(FastrakParser, DefaultAsciiRecord) {
  ASSERT_EQ(kDefaultAscii.size(), 47u);
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  auto ev = parse_all(p, kDefaultAscii);
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  const FastrakPose& pose = ev[0].pose;
  EXPECT_EQ(pose.station, 1);
  EXPECT_EQ(pose.status, ' ');
  EXPECT_FLOAT_EQ(pose.position[0], 12.5f);
  EXPECT_FLOAT_EQ(pose.position[1], -3.21f);
  EXPECT_FLOAT_EQ(pose.position[2], -123.45f);
  EXPECT_TRUE(pose.has.euler);
  EXPECT_FLOAT_EQ(pose.euler_deg[0], 90.0f);
  EXPECT_FLOAT_EQ(pose.euler_deg[2], 180.0f);
  EXPECT_EQ(p.counters().poses, 1u);
  EXPECT_EQ(p.counters().dropped_bytes, 0u);
}

TEST(FastrakParser, SignColumnStyleAndTouchingFields) {
  // "-  3.21" (manual's sign column) and "-123.45-100.00" touching (§3.2, pitfall 7).
  const std::string rec = std::string("01 ") + "-  3.21" + "-123.45" + "-100.00" + " -10.00" +
                          "  -5.00" + "   1.00" + "\r\n";
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  auto ev = parse_all(p, rec);
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_FLOAT_EQ(ev[0].pose.position[0], -3.21f);
  EXPECT_FLOAT_EQ(ev[0].pose.position[1], -123.45f);
  EXPECT_FLOAT_EQ(ev[0].pose.position[2], -100.0f);
}

TEST(FastrakParser, AsciiFieldSyntaxErrorsAreDropped) {
  for (const char* bad : {" 12.5 ", "  12,50", " 1 2.50", "   .50", "  12.5x", "--12.50"}) {
    std::string field(bad);
    field.resize(7, ' ');
    const std::string rec = std::string("01 ") + field + kDefaultAscii.substr(10);
    FastrakParser p(one_station(Format::ascii, kDefaultList));
    auto ev = parse_all(p, rec);
    ASSERT_EQ(ev.size(), 1u) << bad;
    EXPECT_EQ(ev[0].kind, EventKind::resync) << bad;
    EXPECT_EQ(ev[0].dropped, 47u) << bad;
  }
}

TEST(FastrakParser, AsciiDirectionCosinesAndQuaternion) {
  const std::string dcm = std::string("02 ") + "   1.00" + "   2.00" + "   3.00" + " 1.0000" +
                          " 0.0000" + " 0.0000" + " 0.0000" + " 1.0000" + " 0.0000" + " 0.0000" +
                          " 0.0000" + " 1.0000" + "\r\n";
  FastrakConfig c;
  c.stations[1].enabled = true;
  c.stations[1].list =
      OutputList::of({Item::position, Item::dcm_x, Item::dcm_y, Item::dcm_z, Item::crlf});
  c.stations[2].enabled = true;
  c.stations[2].list = OutputList::of({Item::position, Item::quaternion, Item::crlf});
  const std::string quat = std::string("03 ") + "   1.00" + "   2.00" + "   3.00" + " 0.7071" +
                           " 0.0000" + " 0.0000" + "-0.7071" + "\r\n";
  ASSERT_EQ(dcm.size(), 89u);
  ASSERT_EQ(quat.size(), 54u);
  FastrakParser p(c);
  auto ev = parse_all(p, dcm + quat);
  ASSERT_EQ(ev.size(), 2u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_TRUE(ev[0].pose.has.dcm);
  EXPECT_EQ(ev[0].pose.station, 2);
  EXPECT_FLOAT_EQ(ev[0].pose.dcm[4], 1.0f);
  ASSERT_EQ(ev[1].kind, EventKind::pose);
  EXPECT_TRUE(ev[1].pose.has.quaternion);
  EXPECT_FLOAT_EQ(ev[1].pose.quaternion[3], -0.7071f);
}

TEST(FastrakParser, BinaryVrpnRecordWithStylus) {
  // 2,11,16,0: 34 bytes, floats little-endian, stylus ' ' + '1', trailing space.
  std::string rec = "01 ";
  for (float v : {1.5f, -2.25f, 3.0f, 1.0f, 0.0f, 0.0f, 0.0f}) rec += f32le(v);
  rec += " 1 ";
  ASSERT_EQ(rec.size(), 34u);
  FastrakParser p(one_station(Format::binary, OutputList::of({Item::position, Item::quaternion,
                                                              Item::stylus, Item::space})));
  auto ev = parse_all(p, rec);
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_EQ(ev[0].pose.position[1], -2.25f);
  EXPECT_TRUE(ev[0].pose.has_button);
  EXPECT_TRUE(ev[0].pose.button);
}

TEST(FastrakParser, AsciiStylusWidthIsConfigurable) {
  FastrakConfig c =
      one_station(Format::ascii, OutputList::of({Item::position, Item::stylus, Item::crlf}));
  c.ascii_stylus_width = 2;
  FastrakParser p(c);
  auto ev = parse_all(p, std::string("01 ") + "   1.00   2.00   3.00" + " 1" + "\r\n");
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_TRUE(ev[0].pose.button);
}

TEST(FastrakParser, LetterStatusIsAWarningNotAnError) {
  std::string rec = kDefaultAscii;
  rec[2] = 'y';  // outside the Q envelope
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  auto ev = parse_all(p, rec);
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_EQ(ev[0].pose.status, 'y');
}

TEST(FastrakParser, StatusReply) {
  const std::string status = std::string("21S3F0   ") + " 01" + "3" + "  " + "  3.00" +
                             "OutputCompensat simulator       " + "\r\n";
  ASSERT_EQ(status.size(), 55u);
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  auto ev = parse_all(p, status + kDefaultAscii);
  ASSERT_EQ(ev.size(), 2u);
  ASSERT_EQ(ev[0].kind, EventKind::status);
  EXPECT_EQ(ev[0].status.flags, 0x3F0);
  EXPECT_FALSE(ev[0].status.binary);
  EXPECT_FALSE(ev[0].status.centimetres);
  EXPECT_FALSE(ev[0].status.continuous);
  EXPECT_EQ(ev[1].kind, EventKind::pose);
}

TEST(FastrakParser, StatusFlagsDecodeFormatUnitsMode) {
  std::string status =
      std::string("22S3FB   ") + " 01" + "3" + "  " + "  3.00" + std::string(32, ' ') + "\r\n";
  FastrakParser p(one_station(Format::binary, kDefaultList));
  auto ev = parse_all(p, status);
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::status);
  EXPECT_EQ(ev[0].status.station, 2);
  EXPECT_TRUE(ev[0].status.binary);
  EXPECT_TRUE(ev[0].status.centimetres);
  EXPECT_TRUE(ev[0].status.continuous);
}

TEST(FastrakParser, ReadBackAndCommandErrorReplies) {
  const std::string readback = "21O 2 4 1\r\n";
  const std::string error = "2 E*ERROR* Q1,x *ERROR* EC -2 *PS 3 *FL 1 *ST 0\r\n";
  const std::string enables = "21l1100\r\n";
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  auto ev = parse_all(p, readback + error + enables);
  ASSERT_EQ(ev.size(), 3u);
  ASSERT_EQ(ev[0].kind, EventKind::reply);
  EXPECT_EQ(ev[0].reply.command, 'O');
  EXPECT_EQ(ev[0].reply.length, readback.size());
  ASSERT_EQ(ev[1].kind, EventKind::reply);
  EXPECT_TRUE(ev[1].reply.is_error);
  EXPECT_EQ(ev[1].reply.error_code, -2);
  EXPECT_EQ(ev[2].reply.command, 'l');
  EXPECT_EQ(p.counters().poses, 0u);
}

// §5 "garbage while hunting": one resync per run, then the record.
TEST(FastrakParser, GarbageBeforeRecordGivesOneResync) {
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  auto ev = parse_all(p, "xx\x7f\x01 0 9 garbage" + kDefaultAscii + kDefaultAscii);
  ASSERT_EQ(ev.size(), 3u);
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(ev[0].dropped, 16u);
  EXPECT_EQ(ev[1].kind, EventKind::pose);
  EXPECT_EQ(ev[2].kind, EventKind::pose);
  EXPECT_EQ(p.counters().resyncs, 1u);
}

// §3.7 step 4: a truncated record is rejected one byte at a time and the good record
// that starts inside the rejected candidate is still found.
TEST(FastrakParser, TruncatedRecordThenGoodRecord) {
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  const std::string truncated = kDefaultAscii.substr(0, 30);
  auto ev = parse_all(p, truncated + kDefaultAscii);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(ev[0].dropped, 30u);
  EXPECT_EQ(ev[1].kind, EventKind::pose);
}

TEST(FastrakParser, TruncatedBinaryRecordThenGoodRecords) {
  std::string rec = "01 ";
  for (float v : {10.0f, 20.0f, 30.0f, 1.0f, 0.0f, 0.0f, 0.0f}) rec += f32le(v);
  rec += "\r\n";
  FastrakParser p(
      one_station(Format::binary, OutputList::of({Item::position, Item::quaternion, Item::crlf})));
  auto ev = parse_all(p, rec.substr(0, 20) + rec + rec, {1});
  ASSERT_EQ(ev.size(), 3u);
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(ev[0].dropped, 20u);
  EXPECT_EQ(ev[1].kind, EventKind::pose);
  EXPECT_EQ(ev[2].kind, EventKind::pose);
}

TEST(FastrakParser, MissingTerminatorRejectsCandidate) {
  std::string bad = kDefaultAscii;
  bad[45] = 'X';
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  auto ev = parse_all(p, bad + kDefaultAscii);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(ev[0].dropped, 47u);
  EXPECT_EQ(ev[1].kind, EventKind::pose);
}

TEST(FastrakParser, StationOutOfRangeOrDisabledAndBadStatusCharAreBadHeaders) {
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  std::string s7 = kDefaultAscii;
  s7[1] = '7';
  std::string s2 = kDefaultAscii;
  s2[1] = '2';  // not enabled in our configuration
  std::string bad_status = kDefaultAscii;
  bad_status[2] = '#';
  auto ev = parse_all(p, s7 + s2 + bad_status + kDefaultAscii);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(ev[0].dropped, 3u * 47u);
  EXPECT_EQ(ev[1].kind, EventKind::pose);
}

TEST(FastrakParser, ImplausibleValuesGiveErrorEventsInSpecOrder) {
  auto rec = [](float x, float el, float q0) {
    std::string r = "01 ";
    for (float v : {x, 0.0f, 0.0f, 0.0f, el, 0.0f, q0, 0.0f, 0.0f, 0.0f}) r += f32le(v);
    return r + "\r\n";
  };
  FastrakParser p(one_station(
      Format::binary, OutputList::of({Item::position, Item::euler, Item::quaternion, Item::crlf})));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  auto ev = parse_all(p, rec(nan, 95.0f, 2.0f) + rec(inf, 0.0f, 1.0f) + rec(400.5f, 95.0f, 1.0f) +
                             rec(399.0f, 95.0f, 2.0f) + rec(10.0f, 0.0f, 1.002f) +
                             rec(10.0f, 0.0f, 1.0009f));
  ASSERT_EQ(ev.size(), 6u);
  EXPECT_EQ(ev[0].error, PoseError::nonfinite);
  EXPECT_EQ(ev[1].error, PoseError::nonfinite);
  EXPECT_EQ(ev[2].error, PoseError::position_range);
  EXPECT_EQ(ev[3].error, PoseError::angle_range);
  EXPECT_EQ(ev[4].error, PoseError::bad_quaternion);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(ev[static_cast<std::size_t>(i)].kind, EventKind::error);
    EXPECT_EQ(ev[static_cast<std::size_t>(i)].station, 1);
  }
  EXPECT_EQ(ev[5].kind, EventKind::pose);
  EXPECT_EQ(p.counters().errors, 5u);
  EXPECT_EQ(p.counters().resyncs, 0u);  // framed records are consumed, not dropped
}

TEST(FastrakParser, PositionRangeDependsOnUnits) {
  const std::string rec = std::string("01 ") + " 500.00" + "   0.00" + "   0.00" + "   0.00" +
                          "   0.00" + "   0.00" + "\r\n";
  FastrakParser inches(one_station(Format::ascii, kDefaultList, Units::inches));
  FastrakParser cm(one_station(Format::ascii, kDefaultList, Units::centimetres));
  EXPECT_EQ(parse_all(inches, rec)[0].kind, EventKind::error);
  EXPECT_EQ(parse_all(cm, rec)[0].kind, EventKind::pose);
}

TEST(FastrakParser, NonOrthonormalDcmIsRejected) {
  auto rec = [](std::array<float, 9> m) {
    std::string r = "01 " + f32le(1) + f32le(2) + f32le(3);
    for (float v : m) r += f32le(v);
    return r + "\r\n";
  };
  FastrakParser p(one_station(
      Format::binary,
      OutputList::of({Item::position, Item::dcm_x, Item::dcm_y, Item::dcm_z, Item::crlf})));
  auto ev =
      parse_all(p, rec({1, 0, 0, 0, 1, 0, 0, 0, 1}) + rec({1, 0, 0, 0, 1.01f, 0, 0, 0, 1}) +
                       rec({1, 0, 0, 0, -1, 0, 0, 0, 1}) + rec({1, 0.01f, 0, 0, 1, 0, 0, 0, 1}));
  ASSERT_EQ(ev.size(), 4u);
  EXPECT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_EQ(ev[1].error, PoseError::bad_dcm);  // column norm
  EXPECT_EQ(ev[2].error, PoseError::bad_dcm);  // det <= 0
  EXPECT_EQ(ev[3].error, PoseError::bad_dcm);  // columns not orthogonal
}

// False header matches inside binary payloads (pitfall 6) must not lose records.
TEST(FastrakParser, FalseHeaderInsideBinaryPayload) {
  // y = bytes "01 A" as a float: a '0','1',' ' inside the payload.
  std::string payload_hdr = "01 A";
  float y;
  std::memcpy(&y, payload_hdr.data(), 4);
  ASSERT_TRUE(std::isfinite(y));
  std::string rec = "01 " + f32le(1.0f) + f32le(y < 300 && y > -300 ? y : 5.0f) + f32le(3.0f) +
                    f32le(1) + f32le(0) + f32le(0) + f32le(0) + "\r\n";
  FastrakParser p(
      one_station(Format::binary, OutputList::of({Item::position, Item::quaternion, Item::crlf})));
  auto ev = parse_all(p, "0" + rec + rec + "\r\n01" + rec, {3});
  std::size_t poses = 0;
  for (const auto& e : ev) poses += e.kind == EventKind::pose;
  EXPECT_EQ(poses, 3u);
}

TEST(FastrakParser, TwoStationsWithDifferentListsInterleaved) {
  FastrakConfig c = one_station(Format::ascii, kDefaultList);
  c.stations[1].enabled = true;
  c.stations[1].list = OutputList::of({Item::position, Item::space});
  const std::string s2 = std::string("02 ") + "   4.00   5.00   6.00" + " ";
  FastrakParser p(c);
  auto ev = parse_all(p, kDefaultAscii + s2 + s2 + kDefaultAscii, {5});
  ASSERT_EQ(ev.size(), 4u);
  EXPECT_EQ(ev[0].pose.station, 1);
  EXPECT_EQ(ev[1].pose.station, 2);
  EXPECT_EQ(ev[2].pose.station, 2);
  EXPECT_EQ(ev[3].pose.station, 1);
}

TEST(FastrakParser, TrailingGarbageIsReportedAtFinish) {
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  auto ev = parse_all(p, kDefaultAscii + "01 12");
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[1].kind, EventKind::resync);
  EXPECT_EQ(ev[1].dropped, 5u);
}

TEST(FastrakParser, ByteAtATimeEqualsWholeStream) {
  const std::string stream = "junk" + kDefaultAscii + kDefaultAscii.substr(0, 12) +
                             "21O 2 4 1\r\n" + kDefaultAscii + "2\x01" + kDefaultAscii;
  FastrakParser a(one_station(Format::ascii, kDefaultList));
  FastrakParser b(one_station(Format::ascii, kDefaultList));
  auto whole = parse_all(a, stream);
  auto bytes = parse_all(b, stream, {1});
  ASSERT_EQ(whole.size(), bytes.size());
  for (std::size_t i = 0; i < whole.size(); ++i) {
    EXPECT_EQ(whole[i].kind, bytes[i].kind);
    EXPECT_EQ(whole[i].dropped, bytes[i].dropped);
    EXPECT_EQ(whole[i].pose, bytes[i].pose);
  }
  EXPECT_EQ(a.counters().bytes, stream.size());
  EXPECT_EQ(b.counters().bytes, stream.size());
}

TEST(FastrakParser, InvalidConfigurationIsRefused) {
  FastrakParser p;
  FastrakConfig none;  // no station enabled
  EXPECT_EQ(p.configure(none).code(), StatusCode::invalid_argument);
  FastrakConfig too_long = one_station(Format::ascii, OutputList{});
  too_long.stations[0].list.count = 32;
  too_long.stations[0].list.items.fill(Item::quaternion_ext);
  EXPECT_EQ(p.configure(too_long).code(), StatusCode::invalid_argument);
  auto ev = parse_all(p, kDefaultAscii);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].kind, EventKind::resync);
}

TEST(FastrakParser, NoHeapAllocationWhileParsing) {
  FastrakParser p(one_station(Format::ascii, kDefaultList));
  const std::string stream = "noise" + kDefaultAscii + kDefaultAscii.substr(0, 20) + kDefaultAscii;
  std::size_t poses = 0;
  EXPECT_NO_ALLOCATIONS({
    for (char c : stream) {
      p.feed(bytes_of(std::string_view(&c, 1)),
             [&](const FastrakEvent& e) { poses += e.kind == EventKind::pose; });
    }
  });
  EXPECT_EQ(poses, 2u);
}

}  // namespace
}  // namespace twister::tracker
