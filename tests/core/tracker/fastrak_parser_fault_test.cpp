// FastrakParser on faulty streams (docs/fastrak-protocol.md §3.7, §3.8, §5): garbage,
// torn and truncated records, bad headers, implausible values, interleaved stations,
// resync.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "allocation_counter.hpp"
#include "tracker_test_util.hpp"
#include "twister/tracker/fastrak_parser.hpp"

namespace twister::tracker {
namespace {

using test::bytes_of;
using test::f32le;
using test::kDefaultAscii;
using test::kDefaultList;
using test::one_station;
using test::parse_all;

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
