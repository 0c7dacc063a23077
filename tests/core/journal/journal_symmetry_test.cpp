// Stroke records under a symmetry group (issue 26, docs/math.md §11): version 5 carries
// the long turns byte, the threshold, the local flag and the group; a stroke without a
// group keeps its version 1-4 bytes, so an older journal replays unchanged (a version 1
// record of the old encoder, as bytes, is kept here) and an older reader refuses only
// the symmetric strokes.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <vector>

#include "twister/journal/journal_record.hpp"

namespace twister::journal {
namespace {

JournalRecord stroke(std::uint8_t hand_mask, double threshold, StrokeSymmetry sym) {
  JournalRecord r;
  r.type = RecordType::stroke;
  r.sequence = 7;
  r.stroke.method = 1;
  r.stroke.hand_mask = hand_mask;
  r.stroke.radius_m = 0.3;
  r.stroke.refine_threshold_m = threshold;
  r.stroke.symmetry = sym;
  for (int h = 0; h < 2; ++h) {
    if ((hand_mask & (1 << h)) != 0) r.stroke.end[h].origin = {0.1, 0.0, 0.2 * h};
  }
  return r;
}

std::span<const std::byte> payload_of(std::span<const std::byte> buf, std::size_t n) {
  return buf.subspan(kRecordHeaderBytes, n - kRecordHeaderBytes - kRecordCrcBytes);
}

// A version 1 stroke record as the encoder wrote it before symmetry (hand 0, rottran,
// radius 0.3, sequence 7, start the identity pose at the origin, end at (0.1, 0, 0)):
// header, payload, CRC.
std::vector<std::byte> old_version_one() {
  JournalRecord r = stroke(1, 0.0, {});
  r.stroke.start[0] = as_stored(r.stroke.start[0]);
  std::array<std::byte, kMaxRecordBytes> buf{};
  const auto n = encode_record(r, buf);
  return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(*n)};
}

// The bytes of old_version_one() from the encoder before issue 26 (commit 5e5ed55).
constexpr unsigned char kOldRecord[] = {
#include "journal_symmetry_v1_record.inc"
};

TEST(JournalSymmetry, AStrokeWithoutSymmetryKeepsItsOldBytes) {
  const std::vector<std::byte> now = old_version_one();
  ASSERT_EQ(now.size(), sizeof kOldRecord);
  EXPECT_EQ(0, std::memcmp(now.data(), kOldRecord, sizeof kOldRecord));
  EXPECT_EQ(std::to_integer<int>(now[4]), kRecordVersion);
  const auto decoded = decode_payload(
      kRecordVersion, 1, payload_of(std::as_bytes(std::span(kOldRecord)), sizeof kOldRecord));
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(decoded->stroke.symmetry, StrokeSymmetry{});
  EXPECT_EQ(decoded->stroke.method, 1);
}

TEST(JournalSymmetry, VersionFiveRoundTripsEveryKind) {
  const StrokeSymmetry kinds[] = {{1, 1, 0, 0},  {1, 7, 0, 0}, {2, 0, 0, 2},
                                  {2, 0, 2, 12}, {3, 0, 1, 6}, {3, 0, 2, 12}};
  for (const StrokeSymmetry& sym : kinds) {
    for (const double threshold : {0.0, 0.002}) {
      for (const bool local : {false, true}) {
        if (local && threshold == 0.0) continue;
        JournalRecord r = stroke(3, threshold, sym);
        r.stroke.refine_local = local;
        r.stroke.long_turns = 2;
        std::array<std::byte, kMaxRecordBytes> buf{};
        const auto n = encode_record(r, buf);
        ASSERT_TRUE(n.ok());
        EXPECT_EQ(std::to_integer<int>(buf[4]), kRecordVersionSymmetric);
        const auto decoded = decode_payload(kRecordVersionSymmetric, 1, payload_of(buf, *n));
        ASSERT_TRUE(decoded.ok());
        EXPECT_EQ(*decoded, r);
        // An older reader (versions 1-4) cannot read it as one of its own.
        for (std::uint8_t v = 1; v <= kRecordVersionRefinedLocal; ++v) {
          EXPECT_FALSE(decode_payload(v, 1, payload_of(buf, *n)).ok());
        }
      }
    }
  }
}

TEST(JournalSymmetry, RefusesGroupsThatAreNoneOrMalformed) {
  std::array<std::byte, kMaxRecordBytes> buf{};
  const StrokeSymmetry bad[] = {{1, 0, 0, 0}, {1, 8, 0, 0}, {1, 1, 1, 0},
                                {2, 0, 3, 6}, {2, 0, 0, 1}, {3, 0, 0, 13},
                                {2, 1, 0, 6}, {4, 0, 0, 0}, {0, 1, 0, 0}};
  for (const StrokeSymmetry& sym : bad) {
    EXPECT_EQ(encode_record(stroke(1, 0.0, sym), buf).status().code(),
              StatusCode::invalid_argument);
  }
  // Bytes that name a bad group (or none) in a version 5 record are not a record.
  const auto n = encode_record(stroke(1, 0.0, {2, 0, 1, 6}), buf);
  ASSERT_TRUE(n.ok());
  const std::size_t kind_at = *n - kRecordCrcBytes - 4;
  for (const std::array<int, 4>& b :
       {std::array<int, 4>{0, 0, 0, 0}, std::array<int, 4>{2, 0, 1, 13},
        std::array<int, 4>{5, 0, 1, 6}, std::array<int, 4>{1, 9, 0, 0}}) {
    std::array<std::byte, kMaxRecordBytes> copy = buf;
    for (std::size_t i = 0; i < 4; ++i) copy[kind_at + i] = static_cast<std::byte>(b[i]);
    EXPECT_FALSE(decode_payload(kRecordVersionSymmetric, 1, payload_of(copy, *n)).ok());
  }
  // The local flag is 0 or 1, and 1 only with a threshold.
  std::array<std::byte, kMaxRecordBytes> copy = buf;
  copy[kind_at - 1] = std::byte{1};
  EXPECT_FALSE(decode_payload(kRecordVersionSymmetric, 1, payload_of(copy, *n)).ok());
}

}  // namespace
}  // namespace twister::journal
