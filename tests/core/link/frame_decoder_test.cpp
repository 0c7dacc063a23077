// FrameDecoder's status contract (pw_hdlc's shape): unavailable while a frame is
// incomplete, the payload when it completes, data_loss for a bad CRC or COBS
// structure, resource_exhausted (once) for a frame larger than the buffer.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "twister/link/link_codec.hpp"

namespace twister::link {
namespace {

// A default message of `type` (the alternative at index type - 1).
template <std::size_t... I>
LinkMessage default_of(MessageType type, std::index_sequence<I...>) {
  LinkMessage m;
  ((static_cast<std::size_t>(type) == I + 1 ? (void)m.emplace<I>() : void()), ...);
  return m;
}

std::vector<std::byte> frame_of(MessageType type) {
  const LinkMessage m = default_of(type, std::make_index_sequence<kLastMessageType>{});
  std::vector<std::byte> out(kMaxFrameBytes);
  const auto n = encode_frame(m, out);
  EXPECT_TRUE(n.ok());
  out.resize(*n);
  return out;
}

// Statuses of feeding `bytes` one by one.
std::vector<StatusCode> codes(FrameDecoder& d, const std::vector<std::byte>& bytes) {
  std::vector<StatusCode> out;
  for (const std::byte b : bytes) out.push_back(d.process(b).status().code());
  return out;
}

TEST(FrameDecoder, UnavailableUntilTheDelimiterThenThePayload) {
  FrameDecoderBuffer<> d;
  const auto frame = frame_of(MessageType::resend_request);
  for (std::size_t i = 0; i + 1 < frame.size(); ++i) {
    EXPECT_EQ(d.process(frame[i]).status().code(), StatusCode::unavailable);
  }
  const auto payload = d.process(frame.back());
  ASSERT_TRUE(payload.ok());
  ASSERT_GE(payload->size(), 2u);
  EXPECT_EQ((*payload)[0], std::byte{kProtocolVersion});
  EXPECT_EQ((*payload)[1], static_cast<std::byte>(MessageType::resend_request));
  EXPECT_EQ(d.counters().frames, 1u);
}

TEST(FrameDecoder, BadCrcAndBrokenCobsAreDataLoss) {
  FrameDecoderBuffer<> d;
  // A changed payload byte: the CRC no longer matches.
  const auto good = frame_of(MessageType::mesh_end);
  std::vector<std::byte> bad = good;
  bad[bad.size() - 3] ^= std::byte{0x40};  // inside the CRC trailer, never 0 after the flip
  ASSERT_NE(bad[bad.size() - 3], std::byte{0});
  EXPECT_EQ(codes(d, bad).back(), StatusCode::data_loss);
  EXPECT_EQ(d.counters().bad_crc, 1u);
  // A COBS code byte pointing past the delimiter.
  const std::vector<std::byte> broken = {std::byte{9}, std::byte{1}, std::byte{0}};
  EXPECT_EQ(codes(d, broken).back(), StatusCode::data_loss);
  EXPECT_EQ(d.counters().bad_cobs, 1u);
  // The next good frame decodes.
  EXPECT_TRUE(codes(d, frame_of(MessageType::hello)).back() == StatusCode::ok);
}

TEST(FrameDecoder, OversizeIsResourceExhaustedOnceThenResyncs) {
  FrameDecoderBuffer<16> small;
  EXPECT_EQ(small.max_size(), 16u);
  std::vector<std::byte> junk(40, std::byte{0x55});
  junk.push_back(std::byte{0});
  const auto got = codes(small, junk);
  EXPECT_EQ(std::count(got.begin(), got.end(), StatusCode::resource_exhausted), 1);
  EXPECT_EQ(got.back(), StatusCode::unavailable);  // the delimiter ends the dropped frame
  EXPECT_EQ(small.counters().oversize, 1u);
  EXPECT_EQ(small.counters().bytes_skipped, 40u);
  // The same bytes fit a larger buffer: then they are no frame (data_loss), not oversize.
  FrameDecoderBuffer<> big;
  EXPECT_EQ(codes(big, junk).back(), StatusCode::data_loss);  // fits, but is no frame
}

TEST(FrameDecoder, ClearDropsAPartialFrame) {
  FrameDecoderBuffer<> d;
  const auto a = frame_of(MessageType::hello);
  for (std::size_t i = 0; i < 5; ++i) ASSERT_FALSE(d.process(a[i]).ok());
  d.clear();  // a new peer: its first frame must not be glued to the stale bytes
  EXPECT_EQ(codes(d, frame_of(MessageType::mesh_end)).back(), StatusCode::ok);
}

TEST(LinkDecoder, RefusedPayloadIsCountedAndReported) {
  // A well-framed message the decoder must refuse: a non-finite radius.
  Hands m;
  m.flags = kStrokeActive;
  m.radius_m = std::numeric_limits<float>::quiet_NaN();
  std::vector<std::byte> out(kMaxFrameBytes);
  const auto n = encode_frame(m, out);
  ASSERT_TRUE(n.ok());
  LinkDecoder d;
  Status last = StatusCode::unavailable;
  for (std::size_t i = 0; i < *n; ++i) last = d.process(out[i]).status();
  EXPECT_EQ(last.code(), StatusCode::invalid_argument);
  EXPECT_EQ(d.counters().frames, 0u);
  EXPECT_EQ(d.counters().bad_payload, 1u);
}

}  // namespace
}  // namespace twister::link
