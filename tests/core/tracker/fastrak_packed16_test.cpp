// The 16-bit packed format (docs/fastrak-protocol.md §3.4, Isotrak II / 3SPACE heritage)
// against byte streams built here from that description, independently of pack16(): 7
// logical bytes per group with bit 7 stripped, then one byte of the stripped bits (bit 0 =
// first byte), the record's first wire byte marked by bit 7.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tracker_test_util.hpp"
#include "twister/tracker/fastrak_encoder.hpp"
#include "twister/tracker/fastrak_parser.hpp"

namespace twister::tracker {
namespace {

using test::one_station;
using test::parse_all;

std::string le16(int v) {
  const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(v));
  return {static_cast<char>(u & 0xFF), static_cast<char>(u >> 8)};
}

// The packing of docs/fastrak-protocol.md §3.4, written out long-hand for the tests.
std::string pack_by_hand(const std::string& logical) {
  std::string wire;
  for (std::size_t g = 0; g < logical.size(); g += 7) {
    unsigned high = 0;
    for (std::size_t i = g; i < std::min(g + 7, logical.size()); ++i) {
      const auto b = static_cast<unsigned char>(logical[i]);
      if (b & 0x80) high |= 1u << (i - g);
      wire += static_cast<char>(b & 0x7F);
    }
    wire += static_cast<char>(high);
  }
  wire[0] = static_cast<char>(static_cast<unsigned char>(wire[0]) | 0x80);
  return wire;
}

const OutputList kVrpnIsotrakList = OutputList::of({Item::position, Item::quaternion});

// Position counts 1000, -1000, 128 and the identity quaternion (32767 counts).
std::string sample_logical(char station = '1') {
  return std::string("0") + station + " " + le16(1000) + le16(-1000) + le16(128) + le16(32767) +
         le16(0) + le16(0) + le16(0);
}

TEST(FastrakPacked16, RecordIs20WireBytesWithOnlyTheFirstMarked) {
  EXPECT_EQ(record_length(kVrpnIsotrakList, Format::binary16), 20u);
  EXPECT_EQ(logical_record_length(kVrpnIsotrakList, Format::binary16), 17u);
  EXPECT_EQ(
      record_length(OutputList::of({Item::position, Item::euler, Item::crlf}), Format::binary16),
      20u);  // 17 logical bytes as well
  EXPECT_EQ(
      record_length(OutputList::of({Item::position, Item::quaternion, Item::stylus, Item::crlf}),
                    Format::binary16),
      24u);  // 21 logical bytes: 7 + 7 + 7 -> 8 + 8 + 8
  const std::string wire = pack_by_hand(sample_logical());
  ASSERT_EQ(wire.size(), 20u);
  EXPECT_EQ(static_cast<unsigned char>(wire[0]), 0xB0);  // '0' | 0x80
  for (std::size_t i = 1; i < wire.size(); ++i) {
    EXPECT_EQ(static_cast<unsigned char>(wire[i]) & 0x80, 0) << i;
  }
}

TEST(FastrakPacked16, DecodesCountsWithTheSpecScales) {
  FastrakParser parser(one_station(Format::binary16, kVrpnIsotrakList));
  auto ev = parse_all(parser, pack_by_hand(sample_logical()));
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  const FastrakPose& p = ev[0].pose;
  EXPECT_EQ(p.station, 1);
  EXPECT_NEAR(p.position[0], 1000 * 65.48 / 32768, 1e-5);
  EXPECT_NEAR(p.position[1], -1000 * 65.48 / 32768, 1e-5);
  EXPECT_NEAR(p.position[2], 128 * 65.48 / 32768, 1e-5);
  EXPECT_FLOAT_EQ(p.quaternion[0], 1.0f);
  EXPECT_TRUE(p.has.quaternion);
  // Centimetres: the same counts span +-166.32 cm.
  FastrakParser cm(one_station(Format::binary16, kVrpnIsotrakList, Units::centimetres));
  auto ev_cm = parse_all(cm, pack_by_hand(sample_logical()));
  ASSERT_EQ(ev_cm.size(), 1u);
  EXPECT_NEAR(ev_cm[0].pose.position[0], 1000 * 166.32 / 32768, 1e-4);
}

TEST(FastrakPacked16, HighBitInsideARecordIsLostSyncAndTheNextRecordDecodes) {
  FastrakParser parser(one_station(Format::binary16, kVrpnIsotrakList));
  std::string bad = pack_by_hand(sample_logical());
  bad[9] = static_cast<char>(static_cast<unsigned char>(bad[9]) | 0x80);
  auto ev = parse_all(parser, bad + pack_by_hand(sample_logical()));
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(ev[0].dropped, 20u);
  EXPECT_EQ(ev[1].kind, EventKind::pose);
}

TEST(FastrakPacked16, UnmarkedRecordTypeAndBadHeaderHighBitsAreNotRecords) {
  FastrakParser parser(one_station(Format::binary16, kVrpnIsotrakList));
  // The logical bytes unpacked ('0' without its sync bit) are not a record here.
  const std::string logical = sample_logical();
  std::string wrong_header = pack_by_hand(logical);
  wrong_header[7] = static_cast<char>(wrong_header[7] | 0x02);  // station byte's high bit
  auto ev = parse_all(parser, logical + wrong_header);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].kind, EventKind::resync);
  EXPECT_EQ(ev[0].dropped, logical.size() + wrong_header.size());
}

TEST(FastrakPacked16, RepliesStayAsciiAndEncoderMatchesTheHandPacking) {
  const FastrakConfig c = one_station(Format::binary16, kVrpnIsotrakList);
  FastrakPose p;
  p.station = 1;
  p.position = {static_cast<float>(1000 * 65.48 / 32768), static_cast<float>(-1000 * 65.48 / 32768),
                static_cast<float>(128 * 65.48 / 32768)};
  p.quaternion = {1.0f, 0.0f, 0.0f, 0.0f};
  std::array<std::byte, 64> buf{};
  auto n = encode_record(p, c, buf);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(buf.data()), *n),
            pack_by_hand(sample_logical()));
  FastrakParser parser(c);
  auto ev = parse_all(parser, "21O 2 11\r\n" + pack_by_hand(sample_logical()));
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, EventKind::reply);
  EXPECT_EQ(ev[1].kind, EventKind::pose);
}

TEST(FastrakPacked16, ExtendedItemsAreRejectedByValidate) {
  EXPECT_FALSE(
      validate(one_station(Format::binary16, OutputList::of({Item::position_ext, Item::crlf})))
          .ok());
  EXPECT_TRUE(validate(one_station(Format::binary16, kVrpnIsotrakList)).ok());
}

TEST(FastrakPacked16, OutOfRangeCountsAreClampedAndImplausibleQuaternionRejected) {
  const FastrakConfig c = one_station(Format::binary16, kVrpnIsotrakList);
  FastrakPose p;
  p.station = 1;
  p.position = {500.0f, -500.0f, 0.0f};  // beyond +-65.48 in: clamped to full scale
  p.quaternion = {1.0f, 0.0f, 0.0f, 0.0f};
  std::array<std::byte, 64> buf{};
  auto n = encode_record(p, c, buf);
  ASSERT_TRUE(n.ok());
  FastrakParser parser(c);
  auto ev = parse_all(parser, std::string(reinterpret_cast<const char*>(buf.data()), *n));
  ASSERT_EQ(ev.size(), 1u);
  ASSERT_EQ(ev[0].kind, EventKind::pose);
  EXPECT_NEAR(ev[0].pose.position[0], 32767 * 65.48 / 32768, 1e-4);
  EXPECT_NEAR(ev[0].pose.position[1], -65.48, 1e-4);
  std::string half =
      std::string("01 ") + le16(0) + le16(0) + le16(0) + le16(16384) + le16(0) + le16(0) + le16(0);
  auto bad = parse_all(parser, pack_by_hand(half));
  ASSERT_EQ(bad.size(), 1u);
  EXPECT_EQ(bad[0].kind, EventKind::error);
  EXPECT_EQ(bad[0].error, PoseError::bad_quaternion);
}

}  // namespace
}  // namespace twister::tracker
