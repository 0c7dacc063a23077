// Stroke records of refined commits (issue 13): record version 3 carries the long
// turns byte and the refinement threshold, written only when the commit refined, so
// unrefined strokes keep their version 1 / 2 bytes and old journals replay unrefined.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cmath>
#include <cstring>

#include "twister/journal/journal_record.hpp"

namespace twister::journal {
namespace {

JournalRecord stroke(std::uint8_t hand_mask, std::uint8_t long_turns, double threshold) {
  JournalRecord r;
  r.type = RecordType::stroke;
  r.sequence = 7;
  r.stroke.hand_mask = hand_mask;
  r.stroke.long_turns = long_turns;
  r.stroke.radius_m = 0.3;
  r.stroke.refine_threshold_m = threshold;
  for (int h = 0; h < 2; ++h) {
    if ((hand_mask & (1 << h)) != 0) r.stroke.end[h].origin = {0.1, 0.0, 0.2 * h};
  }
  return r;
}

std::span<const std::byte> payload_of(const std::array<std::byte, kMaxRecordBytes>& buf,
                                      std::size_t n) {
  return std::span<const std::byte>(buf).subspan(kRecordHeaderBytes,
                                                 n - kRecordHeaderBytes - kRecordCrcBytes);
}

TEST(JournalRefined, VersionThreeOnlyWhenRefined) {
  std::array<std::byte, kMaxRecordBytes> plain{};
  std::array<std::byte, kMaxRecordBytes> refined{};
  const auto plain_n = encode_record(stroke(3, 0, 0.0), plain);
  const auto refined_n = encode_record(stroke(3, 0, 0.002), refined);
  ASSERT_TRUE(plain_n.ok() && refined_n.ok());
  EXPECT_EQ(std::to_integer<int>(plain[4]), 1);
  EXPECT_EQ(std::to_integer<int>(refined[4]), kRecordVersionRefined);
  EXPECT_EQ(*refined_n, *plain_n + 9);  // long turns byte (0 here) + f64 threshold
  EXPECT_EQ(0,
            std::memcmp(plain.data() + 5, refined.data() + 5, *plain_n - 5 - kRecordCrcBytes - 4));
  const auto decoded = decode_payload(3, 1, payload_of(refined, *refined_n));
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(*decoded, stroke(3, 0, 0.002));
}

// Issue 24: a stroke refined over its region only is version 4, version 3's bytes
// otherwise; it decodes with refine_local set; a region flag without a threshold is
// not a record.
TEST(JournalRefined, VersionFourIsVersionThreeRefinedLocally) {
  std::array<std::byte, kMaxRecordBytes> whole{};
  std::array<std::byte, kMaxRecordBytes> local{};
  JournalRecord r = stroke(3, 1, 0.002);
  const auto whole_n = encode_record(r, whole);
  r.stroke.refine_local = true;
  const auto local_n = encode_record(r, local);
  ASSERT_TRUE(whole_n.ok() && local_n.ok());
  EXPECT_EQ(std::to_integer<int>(whole[4]), kRecordVersionRefined);
  EXPECT_EQ(std::to_integer<int>(local[4]), kRecordVersionRefinedLocal);
  ASSERT_EQ(*whole_n, *local_n);
  EXPECT_EQ(0, std::memcmp(whole.data() + 5, local.data() + 5, *local_n - 5 - kRecordCrcBytes));
  const auto decoded = decode_payload(kRecordVersionRefinedLocal, 1, payload_of(local, *local_n));
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(*decoded, r);
  const auto as_three = decode_payload(kRecordVersionRefined, 1, payload_of(whole, *whole_n));
  ASSERT_TRUE(as_three.ok());
  EXPECT_FALSE(as_three->stroke.refine_local);
  JournalRecord no_threshold = stroke(1, 0, 0.0);
  no_threshold.stroke.refine_local = true;
  EXPECT_EQ(encode_record(no_threshold, local).status().code(), StatusCode::invalid_argument);
}

TEST(JournalRefined, RejectsBadThresholdsAndNonCanonicalRecords) {
  std::array<std::byte, kMaxRecordBytes> buf{};
  EXPECT_EQ(encode_record(stroke(1, 0, -1.0), buf).status().code(), StatusCode::invalid_argument);
  EXPECT_EQ(encode_record(stroke(1, 0, std::nan("")), buf).status().code(),
            StatusCode::invalid_argument);
  const auto n = encode_record(stroke(1, 1, 0.01), buf);
  ASSERT_TRUE(n.ok());
  const std::size_t threshold_at = *n - kRecordCrcBytes - 8;
  for (const double bad : {0.0, -0.5, std::nan(""), HUGE_VAL}) {
    std::array<std::byte, kMaxRecordBytes> copy = buf;
    std::memcpy(copy.data() + threshold_at, &bad, 8);
    EXPECT_EQ(decode_payload(3, 1, payload_of(copy, *n)).status().code(), StatusCode::data_loss)
        << bad;
  }
  std::array<std::byte, kMaxRecordBytes> copy = buf;
  copy[threshold_at - 1] = std::byte{2};  // hand 2's turn in a one-hand stroke
  EXPECT_EQ(decode_payload(3, 1, payload_of(copy, *n)).status().code(), StatusCode::data_loss);
  // Version 3 is a stroke-only format, with the refined tail only.
  EXPECT_EQ(decode_payload(2, 1, payload_of(buf, *n)).status().code(), StatusCode::data_loss);
  JournalRecord undo;
  undo.type = RecordType::undo;
  const auto u = encode_record(undo, buf);
  ASSERT_TRUE(u.ok());
  EXPECT_EQ(decode_payload(3, 3, payload_of(buf, *u)).status().code(), StatusCode::data_loss);
}

RC_GTEST_PROP(JournalRefined, RoundTripsEveryCombination, ()) {
  const auto mask = *rc::gen::inRange<std::uint8_t>(1, 4);
  const auto turns = static_cast<std::uint8_t>(*rc::gen::inRange<int>(0, 4) & mask);
  const double threshold = *rc::gen::element(0.0, 1e-5, 0.002, 0.5);
  const JournalRecord r = stroke(mask, turns, threshold);
  std::array<std::byte, kMaxRecordBytes> buf{};
  const auto n = encode_record(r, buf);
  RC_ASSERT(n.ok());
  const auto version = std::to_integer<std::uint8_t>(buf[4]);
  RC_ASSERT(version == (threshold > 0 ? 3 : turns != 0 ? 2 : 1));
  const auto decoded = decode_payload(version, 1, payload_of(buf, *n));
  RC_ASSERT(decoded.ok());
  RC_ASSERT(*decoded == r);
}

}  // namespace
}  // namespace twister::journal
