#include "twister/journal/journal_record.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cstring>

#include "twister/base/checksum.hpp"

namespace twister::journal {
namespace {

Pose random_pose() {
  Pose p;
  auto d = [] { return *rc::gen::map(rc::gen::arbitrary<int>(), [](int i) { return i * 1e-4; }); };
  p.origin = {d(), d(), d()};
  p.u = {d(), d(), d()};
  p.v = {d(), d(), d()};
  return as_stored(p);  // the journal keeps origin, U, V; W = U x V
}

JournalRecord sample_stroke() {
  JournalRecord r;
  r.type = RecordType::stroke;
  r.sequence = 7;
  r.stroke.method = 0;
  r.stroke.hand_mask = 3;
  r.stroke.chain_step = 2;
  r.stroke.radius_m = 0.25;
  r.stroke.start[0].origin = {0.1, 0.2, 0.3};
  r.stroke.end[1].origin = {-0.1, 0.2, 1e-17};
  return r;
}

RC_GTEST_PROP(JournalRecordProperty, EncodeDecodeRoundTrips, ()) {
  JournalRecord r;
  r.type = *rc::gen::element(RecordType::stroke, RecordType::object_move, RecordType::undo,
                             RecordType::redo);
  r.sequence = *rc::gen::arbitrary<std::uint32_t>();
  if (r.type == RecordType::stroke) {
    r.stroke.method = *rc::gen::inRange<std::uint8_t>(0, 3);
    r.stroke.hand_mask = *rc::gen::inRange<std::uint8_t>(1, 4);
    r.stroke.chain_step = *rc::gen::arbitrary<std::uint16_t>();
    r.stroke.radius_m = *rc::gen::inRange(1, 100000) * 1e-5;
    for (int h = 0; h < 2; ++h) {
      if ((r.stroke.hand_mask & (1 << h)) == 0) continue;
      r.stroke.start[h] = random_pose();
      r.stroke.end[h] = random_pose();
    }
  } else if (r.type == RecordType::object_move) {
    r.move.hand = *rc::gen::inRange<std::uint8_t>(0, 2);
    r.move.object_before = random_pose();
    r.move.object_after = random_pose();
  }
  std::array<std::byte, kMaxRecordBytes> buf{};
  const auto n = encode_record(r, buf);
  RC_ASSERT(n.ok());
  std::uint32_t payload = 0;
  std::memcpy(&payload, buf.data(), 4);  // little-endian host in CI
  RC_ASSERT(*n == kRecordHeaderBytes + payload + kRecordCrcBytes);
  const auto back =
      decode_payload(static_cast<std::uint8_t>(buf[4]), static_cast<std::uint8_t>(buf[5]),
                     std::span<const std::byte>(buf).subspan(kRecordHeaderBytes, payload));
  RC_ASSERT(back.ok());
  RC_ASSERT(*back == r);
}

TEST(JournalRecord, CrcCoversHeaderAndPayload) {
  std::array<std::byte, kMaxRecordBytes> buf{};
  const auto n = encode_record(sample_stroke(), buf);
  ASSERT_TRUE(n.ok());
  std::uint32_t stored = 0;
  std::memcpy(&stored, buf.data() + *n - 4, 4);
  EXPECT_EQ(stored, crc32(std::span<const std::byte>(buf).first(*n - 4)));
}

TEST(JournalRecord, RejectsInvalidRecordsOnEncode) {
  std::array<std::byte, kMaxRecordBytes> buf{};
  JournalRecord r = sample_stroke();
  r.stroke.hand_mask = 0;
  EXPECT_EQ(encode_record(r, buf).status().code(), StatusCode::invalid_argument);
  r = sample_stroke();
  r.stroke.method = 3;
  EXPECT_EQ(encode_record(r, buf).status().code(), StatusCode::invalid_argument);
  std::array<std::byte, 16> tiny{};
  EXPECT_EQ(encode_record(sample_stroke(), tiny).status().code(), StatusCode::resource_exhausted);
}

TEST(JournalRecord, RejectsInvalidPayloadsOnDecode) {
  std::array<std::byte, kMaxRecordBytes> buf{};
  const auto n = encode_record(sample_stroke(), buf);
  ASSERT_TRUE(n.ok());
  const auto payload = std::span<const std::byte>(buf).subspan(kRecordHeaderBytes, *n - 12);
  EXPECT_TRUE(decode_payload(1, 1, payload).ok());
  EXPECT_EQ(decode_payload(2, 1, payload).status().code(), StatusCode::data_loss);  // version
  EXPECT_EQ(decode_payload(1, 9, payload).status().code(), StatusCode::data_loss);  // type
  EXPECT_EQ(decode_payload(1, 1, payload.first(payload.size() - 1)).status().code(),
            StatusCode::data_loss);  // length
  EXPECT_EQ(decode_payload(1, 3, payload).status().code(),
            StatusCode::data_loss);  // undo is 4 bytes
  std::array<std::byte, kMaxRecordBytes> bad = buf;
  bad[kRecordHeaderBytes + 8] = std::byte{0xff};  // radius high byte -> NaN/negative
  bad[kRecordHeaderBytes + 15] = std::byte{0xff};
  EXPECT_EQ(decode_payload(
                1, 1, std::span<const std::byte>(bad).subspan(kRecordHeaderBytes, payload.size()))
                .status()
                .code(),
            StatusCode::data_loss);
}

}  // namespace
}  // namespace twister::journal
