// LibertyParser against golden frames written by hand from the layout of
// docs/liberty-protocol.md §2-§3 (not from the encoder), and on faulty streams: noise,
// truncated frames, wrong tags, stations, commands, sizes (oversize never waited for),
// trailers, implausible values.
#include "twister/tracker/liberty_parser.hpp"

#include <gtest/gtest.h>

#include <array>
#include <span>
#include <string>

#include "liberty_test_util.hpp"

namespace twister::tracker {
namespace {

using test::hex;
using test::liberty_one_station;
using test::parse_all;
using L = LibertyItem;

const LibertyOutputList kPosQuatCrlf = LibertyOutputList::of({L::position, L::quaternion, L::crlf});

// Liberty, station 1, continuous, no error, size 30 (body); x y z = 1, 2, -1.5;
// quaternion w x y z = 0.5 each; CR LF. 38 bytes.
const std::string kLibertyGolden =
    hex("4C 59 01 43 00 00 1E 00 | 00 00 80 3F  00 00 00 40  00 00 C0 BF |"
        "00 00 00 3F  00 00 00 3F  00 00 00 3F  00 00 00 3F | 0D 0A");

// Patriot, station 2, polled, default list (position, Euler, CR LF), size 26;
// x y z = 0.5, -1.5, 2; azimuth, elevation, roll = 90, 0, 180. 34 bytes.
const std::string kPatriotGolden =
    hex("50 41 02 50 00 00 1A 00 | 00 00 00 3F  00 00 C0 BF  00 00 00 40 |"
        "00 00 B4 42  00 00 00 00  00 00 34 43 | 0D 0A");

// Latus, station 1, VRPN's list (position, quaternion, timestamp, stylus, space), size 37;
// x y z = 2, 0, 0; quaternion 1 0 0 0; timestamp 1000 ms; stylus pressed; space.
const std::string kLatusGolden =
    hex("4C 55 01 43 00 00 25 00 | 00 00 00 40  00 00 00 00  00 00 00 00 |"
        "00 00 80 3F  00 00 00 00  00 00 00 00  00 00 00 00 | E8 03 00 00 | 01 00 00 00 | 20");

FastrakPose liberty_golden_pose() {
  FastrakPose p;
  p.station = 1;
  p.has_position = true;
  p.position = {1.0f, 2.0f, -1.5f};
  p.has.quaternion = true;
  p.quaternion = {0.5f, 0.5f, 0.5f, 0.5f};
  return p;
}

TEST(LibertyParser, GoldenLibertyFrame) {
  ASSERT_EQ(kLibertyGolden.size(), 38u);
  LibertyParser parser(liberty_one_station(LibertyModel::liberty, kPosQuatCrlf));
  auto ev = parse_all(parser, kLibertyGolden);
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_EQ(ev[0].pose, liberty_golden_pose());
  EXPECT_EQ(parser.counters().poses, 1u);
  EXPECT_EQ(parser.counters().bytes, 38u);
  EXPECT_EQ(parser.counters().dropped_bytes, 0u);
}

TEST(LibertyParser, GoldenPatriotPolledFrame) {
  ASSERT_EQ(kPatriotGolden.size(), 34u);
  LibertyParser parser(
      liberty_one_station(LibertyModel::patriot, LibertyStationConfig{}.list, /*station=*/2));
  auto ev = parse_all(parser, kPatriotGolden, {1});
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  const FastrakPose& p = ev[0].pose;
  EXPECT_EQ(p.station, 2);
  EXPECT_EQ(p.status, ' ');
  EXPECT_TRUE(p.has_position);
  EXPECT_TRUE(p.has.euler);
  EXPECT_FALSE(p.has.quaternion);
  EXPECT_EQ(p.position, (std::array<float, 3>{0.5f, -1.5f, 2.0f}));
  EXPECT_EQ(p.euler_deg, (std::array<float, 3>{90.0f, 0.0f, 180.0f}));
}

TEST(LibertyParser, GoldenLatusFrameWithTimestampAndStylus) {
  ASSERT_EQ(kLatusGolden.size(), 45u);
  LibertyParser parser(liberty_one_station(
      LibertyModel::latus,
      LibertyOutputList::of({L::position, L::quaternion, L::timestamp, L::stylus, L::space})));
  auto ev = parse_all(parser, kLatusGolden + kLatusGolden, {7});
  ASSERT_EQ(ev.size(), 2u);
  ASSERT_EQ(ev[1].kind, EventKind::pose);
  EXPECT_TRUE(ev[1].pose.has_button);
  EXPECT_TRUE(ev[1].pose.button);
  EXPECT_EQ(ev[1].pose.position, (std::array<float, 3>{2.0f, 0.0f, 0.0f}));
  EXPECT_EQ(ev[1].pose.quaternion, (std::array<float, 4>{1.0f, 0.0f, 0.0f, 0.0f}));
}

TEST(LibertyParser, SizeFieldCountingTheWholeFrame) {
  LibertyConfig c = liberty_one_station(LibertyModel::liberty, kPosQuatCrlf);
  c.size_field = LibertySizeField::frame;
  std::string frame = kLibertyGolden;
  frame[6] = 0x26;  // 38: header included
  LibertyParser parser(c);
  auto ev = parse_all(parser, frame + kLibertyGolden);
  // The body-counted frame is now the wrong size: rejected, its bytes dropped.
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_EQ(ev[1].kind, EventKind::resync);
  EXPECT_EQ(ev[1].dropped, 38u);
  EXPECT_EQ(parser.counters().bad_frames, 1u);
  // And the other way round under the default (body) convention.
  LibertyParser body(liberty_one_station(LibertyModel::liberty, kPosQuatCrlf));
  auto ev2 = parse_all(body, frame + kLibertyGolden);
  ASSERT_EQ(ev2.size(), 2u);
  EXPECT_EQ(ev2[0].kind, EventKind::resync);
  EXPECT_EQ(ev2[1].kind, EventKind::pose);
}

TEST(LibertyParser, NoiseBeforeAndBetweenFramesGivesOneResyncPerRun) {
  LibertyParser parser(liberty_one_station(LibertyModel::liberty, kPosQuatCrlf));
  auto ev = parse_all(parser, "xx\r\n\x01" + kLibertyGolden + "LLL" + kLibertyGolden);
  ASSERT_EQ(ev.size(), 4u);
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(ev[0].dropped, 5u);
  EXPECT_EQ(ev[1].kind, EventKind::pose);
  EXPECT_EQ(ev[2].kind, EventKind::resync);
  EXPECT_EQ(ev[2].dropped, 3u);
  EXPECT_EQ(ev[3].kind, EventKind::pose);
  EXPECT_EQ(parser.counters().resyncs, 2u);
  EXPECT_EQ(parser.counters().bad_frames, 0u);  // 'L' alone is noise, not a frame
}

TEST(LibertyParser, TruncatedFramesAreSkippedAndCounted) {
  for (std::size_t cut = 2; cut < kLibertyGolden.size(); ++cut) {
    SCOPED_TRACE(cut);
    LibertyParser parser(liberty_one_station(LibertyModel::liberty, kPosQuatCrlf));
    auto ev =
        parse_all(parser, kLibertyGolden.substr(0, cut) + kLibertyGolden + kLibertyGolden, {3});
    // Cut inside the header the next frame is always found; cut inside the body the
    // remains of the next frame may be taken for the cut frame's body (a frame has no
    // checksum), but the stream recovers by the frame after.
    ASSERT_GE(ev.size(), 2u);
    EXPECT_EQ(ev.back().kind, EventKind::pose);
    EXPECT_EQ(ev.back().pose, liberty_golden_pose());
    if (cut < kLibertyHeaderBytes) {
      ASSERT_EQ(ev.size(), 3u);
      EXPECT_EQ(ev[0].kind, EventKind::resync);
      EXPECT_EQ(ev[0].dropped, cut);
      EXPECT_EQ(parser.counters().poses, 2u);
      EXPECT_EQ(parser.counters().bad_frames, 1u);
    }
  }
}

TEST(LibertyParser, TruncatedFrameAtEndOfStreamIsCountedOnFinish) {
  LibertyParser parser(liberty_one_station(LibertyModel::liberty, kPosQuatCrlf));
  auto ev = parse_all(parser, kLibertyGolden + kLibertyGolden.substr(0, 20));
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_EQ(ev[1].kind, EventKind::resync);
  EXPECT_EQ(ev[1].dropped, 20u);
  EXPECT_EQ(parser.counters().bad_frames, 1u);
  EXPECT_EQ(parser.counters().bytes, 58u);
}

TEST(LibertyParser, OversizeFrameIsRejectedWithoutWaitingForItsBytes) {
  LibertyParser parser(liberty_one_station(LibertyModel::liberty, kPosQuatCrlf));
  const std::string huge = hex("4C 59 01 43 00 00 FF FF");
  std::vector<FastrakEvent> ev;
  parser.feed(test::bytes_of(huge + kLibertyGolden),
              [&](const FastrakEvent& e) { ev.push_back(e); });
  ASSERT_EQ(ev.size(), 2u);  // no finish(): nothing waits for 65535 bytes
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(ev[0].dropped, 8u);
  EXPECT_EQ(ev[1].kind, EventKind::pose);
  EXPECT_EQ(parser.counters().oversize, 1u);
  EXPECT_EQ(parser.counters().bad_frames, 1u);
  // One above the bound is rejected as well; the bound itself is only a wrong size here.
  LibertyParser p2(liberty_one_station(LibertyModel::liberty, kPosQuatCrlf));
  parse_all(p2, hex("4C 59 01 43 00 00 F1 00") + hex("4C 59 01 43 00 00 F0 00"));
  EXPECT_EQ(p2.counters().oversize, 1u);
  EXPECT_EQ(p2.counters().bad_frames, 2u);
}

TEST(LibertyParser, BadHeadersAreRejected) {
  LibertyConfig c = liberty_one_station(LibertyModel::liberty, kPosQuatCrlf);
  auto with = [](std::size_t i, char v) {
    std::string f = kLibertyGolden;
    f[i] = v;
    return f;
  };
  const std::string cases[] = {
      with(2, 0),     // station 0
      with(2, 17),    // beyond 16
      with(2, 2),     // not enabled
      with(3, 'O'),   // not a data command
      with(6, 0x1D),  // size one short of the list's body
      with(36, ' '),  // CR LF trailer broken
  };
  for (const std::string& bad : cases) {
    LibertyParser parser(c);
    auto ev = parse_all(parser, bad + kLibertyGolden);
    ASSERT_EQ(ev.size(), 2u);
    EXPECT_EQ(ev[0].kind, EventKind::resync);
    EXPECT_EQ(ev[0].dropped, 38u);
    EXPECT_EQ(ev[1].kind, EventKind::pose);
    EXPECT_EQ(parser.counters().bad_frames, 1u);
  }
}

TEST(LibertyParser, OtherModelsTagsAreNoise) {
  LibertyParser parser(liberty_one_station(LibertyModel::patriot, kPosQuatCrlf));
  auto ev = parse_all(parser, kLibertyGolden);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(parser.counters().poses, 0u);
}

TEST(LibertyParser, ErrorByteIsTheStatusAndImplausibleValuesAreErrors) {
  LibertyParser parser(liberty_one_station(LibertyModel::liberty, kPosQuatCrlf));
  std::string warn = kLibertyGolden;
  warn[4] = 'A';
  std::string bad_quat = kLibertyGolden;
  bad_quat[8 + 12 + 3] = 0x40;  // w = 2
  std::string far = kLibertyGolden;
  far[8 + 3] = 0x44;  // x = 1024 in
  auto ev = parse_all(parser, warn + bad_quat + far);
  ASSERT_EQ(ev.size(), 3u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_EQ(ev[0].pose.status, 'A');
  ASSERT_EQ(ev[1].kind, EventKind::error);
  EXPECT_EQ(ev[1].error, PoseError::bad_quaternion);
  ASSERT_EQ(ev[2].kind, EventKind::error);
  EXPECT_EQ(ev[2].error, PoseError::position_range);
  EXPECT_EQ(parser.counters().errors, 2u);
  EXPECT_EQ(parser.counters().dropped_bytes, 0u);
}

TEST(LibertyParser, DirectionCosinesAreOneItem) {
  LibertyParser parser(
      liberty_one_station(LibertyModel::liberty, LibertyOutputList::of({L::dcm, L::space})));
  std::string f = hex("4C 59 01 43 00 00 25 00");
  const std::string one = hex("00 00 80 3F"), zero = hex("00 00 00 00");
  f += one + zero + zero + zero + one + zero + zero + zero + one + " ";
  auto ev = parse_all(parser, f);
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_TRUE(ev[0].pose.has.dcm);
  EXPECT_FALSE(ev[0].pose.has_position);
  EXPECT_EQ(ev[0].pose.dcm[4], 1.0f);
}

TEST(LibertyParser, InvalidConfigurationDropsEverything) {
  LibertyParser parser(LibertyConfig{});  // no station enabled
  EXPECT_EQ(parser.configure(LibertyConfig{}).code(), StatusCode::invalid_argument);
  const auto ev = parse_all(parser, kLibertyGolden);
  ASSERT_EQ(ev.size(), 1u);  // finish() reports the dropped run
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(parser.counters().poses, 0u);
  EXPECT_EQ(parser.counters().dropped_bytes, 38u);
  LibertyConfig too_long = liberty_one_station(LibertyModel::liberty, {});
  for (int i = 0; i < 7; ++i)
    too_long.stations[0].list.items[too_long.stations[0].list.count++] = L::dcm;
  EXPECT_EQ(validate(too_long).code(), StatusCode::invalid_argument);  // 252 > 240
}

TEST(LibertyWire, FastrakListsTranslateItemForItem) {
  LibertyOutputList out;
  ASSERT_TRUE(to_liberty_list(
                  OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf}), out)
                  .ok());
  ASSERT_EQ(out.count, 4);
  EXPECT_EQ(out.items[1], L::quaternion);
  EXPECT_EQ(out.items[2], L::stylus);
  EXPECT_EQ(liberty_body_length(out), 12u + 16u + 4u + 2u);
  ASSERT_TRUE(
      to_liberty_list(OutputList::of({Item::dcm_x, Item::dcm_y, Item::dcm_z, Item::space}), out)
          .ok());
  EXPECT_EQ(out.count, 2);
  EXPECT_EQ(out.items[0], L::dcm);
}

TEST(LibertyWire, FastrakConfigTranslatesStationForStation) {
  FastrakConfig f;
  f.units = Units::centimetres;
  f.stations[1] = {true, OutputList::of({Item::position, Item::euler, Item::crlf})};
  LibertyConfig c;
  ASSERT_TRUE(to_liberty_config(f, LibertyModel::patriot, c).ok());
  EXPECT_EQ(c.model, LibertyModel::patriot);
  EXPECT_EQ(c.units, Units::centimetres);
  EXPECT_FALSE(c.stations[0].enabled);
  EXPECT_TRUE(c.stations[1].enabled);
  EXPECT_EQ(liberty_body_length(c.stations[1].list), 26u);
  EXPECT_TRUE(validate(c).ok());
}

TEST(LibertyWire, OutputListCommandUsesTheFamilysItemCodes) {
  // The station's lists: position, quaternion, stylus, CR LF = codes 2, 7, 10, 1 (§3).
  LibertyOutputList list;
  ASSERT_TRUE(
      to_liberty_list(OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf}),
                      list)
          .ok());
  std::array<char, 32> buf{};
  auto n = encode_liberty_output_list(1, list, buf);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(std::string(buf.data(), *n), "O1,2,7,10,1\r");
  n = encode_liberty_output_list(16, LibertyOutputList::of({L::dcm, L::space}), buf);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(std::string(buf.data(), *n), "O16,6,0\r");
  EXPECT_EQ(encode_liberty_output_list(0, list, buf).status().code(), StatusCode::invalid_argument);
  EXPECT_EQ(encode_liberty_output_list(17, list, buf).status().code(),
            StatusCode::invalid_argument);
  EXPECT_EQ(encode_liberty_output_list(1, {}, buf).status().code(), StatusCode::invalid_argument);
  EXPECT_EQ(encode_liberty_output_list(1, list, std::span<char>(buf).first(11)).status().code(),
            StatusCode::out_of_range);
  EXPECT_TRUE(encode_liberty_output_list(1, list, std::span<char>(buf).first(12)).ok());
}

TEST(LibertyWire, LibertyListsTranslateBackToFastrakLists) {
  const OutputList station =
      OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf});
  LibertyOutputList liberty;
  ASSERT_TRUE(to_liberty_list(station, liberty).ok());
  OutputList back;
  ASSERT_TRUE(to_fastrak_list(liberty, back).ok());
  ASSERT_EQ(back.count, station.count);
  for (std::size_t i = 0; i < back.count; ++i) EXPECT_EQ(back.items[i], station.items[i]);
  ASSERT_TRUE(
      to_fastrak_list(LibertyOutputList::of({L::position_ext, L::dcm, L::space}), back).ok());
  ASSERT_EQ(back.count, 5);
  EXPECT_EQ(back.items[0], Item::position);
  EXPECT_EQ(back.items[1], Item::dcm_x);
  EXPECT_EQ(back.items[3], Item::dcm_z);
  EXPECT_EQ(back.items[4], Item::space);
  for (L none : {L::timestamp, L::frame_count, L::distortion}) {
    EXPECT_EQ(to_fastrak_list(LibertyOutputList::of({L::position, none}), back).code(),
              StatusCode::invalid_argument);
  }
}

}  // namespace
}  // namespace twister::tracker
