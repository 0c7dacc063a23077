// FastrakParser against byte streams written from docs/fastrak-protocol.md (§3.2, §3.3,
// §3.6, §3.7, §3.8, §5): record layouts, replies, and every documented fault case.
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
using test::kDefaultAscii;
using test::kDefaultList;
using test::one_station;
using test::parse_all;

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
  // Our source material said 41 (= 3 + 36 + 2) for 2,5,6,7,1, which leaves out the 12
  // position bytes; 41 is the length of 5,6,7,1 and 2,5,6,7,1 is 53
  // (docs/fastrak-protocol.md §3.3).
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

}  // namespace
}  // namespace twister::tracker
