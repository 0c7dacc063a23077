// Stroke records of turns past a half turn (issue "a session"): record version 2 with
// the long_turns byte, written only when some hand turned the long way, so every
// other record keeps version 1 and its exact bytes. Label interaction.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cstring>

#include "twister/journal/journal_record.hpp"

namespace twister::journal {
namespace {

JournalRecord stroke(std::uint8_t hand_mask, std::uint8_t long_turns) {
  JournalRecord r;
  r.type = RecordType::stroke;
  r.sequence = 3;
  r.stroke.hand_mask = hand_mask;
  r.stroke.long_turns = long_turns;
  r.stroke.radius_m = 0.3;
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

TEST(JournalLongTurn, VersionTwoOnlyWithALongTurn) {
  std::array<std::byte, kMaxRecordBytes> a{};
  std::array<std::byte, kMaxRecordBytes> b{};
  const auto short_n = encode_record(stroke(2, 0), a);
  const auto long_n = encode_record(stroke(2, 2), b);
  ASSERT_TRUE(short_n.ok() && long_n.ok());
  EXPECT_EQ(std::to_integer<int>(a[4]), 1);
  EXPECT_EQ(std::to_integer<int>(b[4]), 2);
  EXPECT_EQ(*long_n, *short_n + 1);
  // The long record is the short one plus the mask byte (before the CRC).
  EXPECT_EQ(0, std::memcmp(a.data() + 5, b.data() + 5, *short_n - 5 - kRecordCrcBytes - 1));
  EXPECT_EQ(std::to_integer<int>(b[*long_n - kRecordCrcBytes - 1]), 2);
  const auto decoded = decode_payload(2, 1, payload_of(b, *long_n));
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(*decoded, stroke(2, 2));
}

TEST(JournalLongTurn, RejectsMasksOutsideTheHandsAndNonCanonicalRecords) {
  std::array<std::byte, kMaxRecordBytes> buf{};
  EXPECT_EQ(encode_record(stroke(1, 2), buf).status().code(), StatusCode::invalid_argument);
  const auto n = encode_record(stroke(3, 1), buf);
  ASSERT_TRUE(n.ok());
  const std::size_t mask_at = *n - kRecordCrcBytes - 1;
  for (const int bad : {0, 4, 7}) {  // no long hand (must be version 1), hand 2, too many
    std::array<std::byte, kMaxRecordBytes> copy = buf;
    copy[mask_at] = static_cast<std::byte>(bad);
    EXPECT_EQ(decode_payload(2, 1, payload_of(copy, *n)).status().code(), StatusCode::data_loss)
        << bad;
  }
  // Version 2 is a stroke-only format; undo stays version 1.
  JournalRecord undo;
  undo.type = RecordType::undo;
  const auto u = encode_record(undo, buf);
  ASSERT_TRUE(u.ok());
  EXPECT_EQ(decode_payload(2, 3, payload_of(buf, *u)).status().code(), StatusCode::data_loss);
  EXPECT_TRUE(decode_payload(1, 3, payload_of(buf, *u)).ok());
}

RC_GTEST_PROP(JournalLongTurn, RoundTripsEveryMask, ()) {
  const auto mask = *rc::gen::inRange<std::uint8_t>(1, 4);
  const auto turns = static_cast<std::uint8_t>(*rc::gen::inRange<int>(0, 4) & mask);
  const JournalRecord r = stroke(mask, turns);
  std::array<std::byte, kMaxRecordBytes> buf{};
  const auto n = encode_record(r, buf);
  RC_ASSERT(n.ok());
  const auto decoded =
      decode_payload(std::to_integer<std::uint8_t>(buf[4]), 1, payload_of(buf, *n));
  RC_ASSERT(decoded.ok());
  RC_ASSERT(*decoded == r);
}

}  // namespace
}  // namespace twister::journal
