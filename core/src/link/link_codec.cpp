// COBS framing with a CRC-32 trailer. COBS was chosen over byte stuffing because its
// overhead is bounded (1 byte per 254), so a frame's worst-case size is a constant
// and both sides can use fixed buffers.
#include "twister/link/link_codec.hpp"

#include <utility>

#include "link_payload.hpp"
#include "twister/base/checksum.hpp"

namespace twister::link {
namespace {

constexpr std::size_t kCrcBytes = 4;

// COBS-encodes `in` into `out` followed by the 0x00 delimiter; 0 when it does not fit.
std::size_t cobs_encode(std::span<const std::byte> in, std::span<std::byte> out) {
  std::size_t code_pos = 0;
  std::size_t pos = 1;
  std::uint8_t code = 1;
  if (out.empty()) return 0;
  for (const std::byte b : in) {
    if (b != std::byte{0}) {
      if (pos >= out.size()) return 0;
      out[pos++] = b;
      ++code;
    }
    if (b == std::byte{0} || code == 0xff) {
      out[code_pos] = static_cast<std::byte>(code);
      code = 1;
      code_pos = pos;
      if (pos >= out.size()) return 0;
      ++pos;
    }
  }
  out[code_pos] = static_cast<std::byte>(code);
  if (pos >= out.size()) return 0;
  out[pos++] = std::byte{0};
  return pos;
}

// Decodes in place; returns the decoded length or -1 when the structure is broken.
long cobs_decode(std::span<std::byte> buf) {
  std::size_t in = 0;
  std::size_t out = 0;
  while (in < buf.size()) {
    const auto code = std::to_integer<std::uint8_t>(buf[in]);
    if (code == 0 || in + code > buf.size()) return -1;
    ++in;
    for (std::uint8_t i = 1; i < code; ++i) buf[out++] = buf[in++];
    if (code != 0xff && in < buf.size()) buf[out++] = std::byte{0};
  }
  return static_cast<long>(out);
}

}  // namespace

// The alternatives are in type order: index + 1 is the type byte.
template <std::size_t... I>
constexpr bool alternatives_in_type_order(std::index_sequence<I...>) {
  return ((static_cast<std::size_t>(std::variant_alternative_t<I, LinkMessage>::kType) == I + 1) &&
          ...);
}
static_assert(alternatives_in_type_order(std::make_index_sequence<kLastMessageType>{}));

template <LinkBody M>
Result<std::size_t> encode_frame(const M& message, std::span<std::byte> out) {
  std::array<std::byte, kMaxPayload + kCrcBytes> payload{};
  internal::ByteWriter w(std::span<std::byte>(payload).first(kMaxPayload));
  w.u8(kProtocolVersion);
  w.u8(static_cast<std::uint8_t>(M::kType));
  if (!internal::write_body(w, message)) return StatusCode::invalid_argument;
  if (!w.ok()) return StatusCode::invalid_argument;  // cannot happen within the caps
  const std::size_t n = w.size();
  const std::uint32_t crc = crc32(std::span<const std::byte>(payload).first(n));
  internal::ByteWriter(std::span<std::byte>(payload).subspan(n)).u32(crc);
  const std::size_t written =
      cobs_encode(std::span<const std::byte>(payload).first(n + kCrcBytes), out);
  if (written == 0) return StatusCode::resource_exhausted;
  return written;
}

Result<std::size_t> encode_frame(const LinkMessage& message, std::span<std::byte> out) {
  return std::visit([out](const auto& m) { return encode_frame(m, out); }, message);
}

template <LinkBody M>
std::size_t frame_size(const M& message) {
  std::array<std::byte, kMaxFrameBytes> out{};
  const Result<std::size_t> n = encode_frame(message, out);
  return n.ok() ? *n : 0;
}

std::size_t frame_size(const LinkMessage& message) {
  return std::visit([](const auto& m) { return frame_size(m); }, message);
}

#define TWISTER_LINK_INSTANTIATE(M)                                             \
  template Result<std::size_t> encode_frame<M>(const M&, std::span<std::byte>); \
  template std::size_t frame_size<M>(const M&);
TWISTER_LINK_INSTANTIATE(Hello)
TWISTER_LINK_INSTANTIATE(Auth)
TWISTER_LINK_INSTANTIATE(Bye)
TWISTER_LINK_INSTANTIATE(MeshBegin)
TWISTER_LINK_INSTANTIATE(Vertices)
TWISTER_LINK_INSTANTIATE(Triangles)
TWISTER_LINK_INSTANTIATE(MeshEnd)
TWISTER_LINK_INSTANTIATE(ResendRequest)
TWISTER_LINK_INSTANTIATE(StrokeBegin)
TWISTER_LINK_INSTANTIATE(Hands)
TWISTER_LINK_INSTANTIATE(ObjectPose)
TWISTER_LINK_INSTANTIATE(StatusReport)
TWISTER_LINK_INSTANTIATE(Command)
TWISTER_LINK_INSTANTIATE(Workspace)
TWISTER_LINK_INSTANTIATE(VisitorState)
TWISTER_LINK_INSTANTIATE(Notice)
#undef TWISTER_LINK_INSTANTIATE

Status decode_payload(std::span<const std::byte> payload, LinkMessage& out) {
  internal::ByteReader r(payload);
  const std::uint8_t version = r.u8();
  const std::uint8_t type = r.u8();
  if (!r.ok()) return StatusCode::invalid_argument;
  if (version != kProtocolVersion) return StatusCode::not_supported;
  if (type < 1 || type > kLastMessageType) {
    return StatusCode::invalid_argument;
  }
  if (!internal::read_body(r, static_cast<MessageType>(type), out)) {
    return StatusCode::invalid_argument;
  }
  return ok_status();
}

void FrameDecoder::clear() {
  size_ = 0;
  overflow_ = false;
}

void LinkDecoder::clear() {
  frames_.clear();
  other_version_seen_ = 0;
}

Result<std::span<const std::byte>> FrameDecoder::process(std::byte byte) {
  if (byte != std::byte{0}) {
    if (overflow_) {
      ++counters_.bytes_skipped;
      return StatusCode::unavailable;
    }
    if (size_ == buffer_.size()) {
      // Too long to be ours: drop everything up to the next delimiter.
      ++counters_.oversize;
      counters_.bytes_skipped += size_ + 1;
      overflow_ = true;
      size_ = 0;
      return StatusCode::resource_exhausted;
    }
    buffer_[size_++] = byte;
    return StatusCode::unavailable;
  }
  if (overflow_) {
    overflow_ = false;
    size_ = 0;
    return StatusCode::unavailable;
  }
  if (size_ == 0) return StatusCode::unavailable;  // back-to-back delimiters: no frame
  auto frame = finish_frame();
  if (!frame.ok()) counters_.bytes_skipped += size_ + 1;
  size_ = 0;
  return frame;
}

Result<std::span<const std::byte>> FrameDecoder::finish_frame() {
  const long decoded = cobs_decode(buffer_.first(size_));
  if (decoded < 0) {
    ++counters_.bad_cobs;
    return StatusCode::data_loss;
  }
  const auto n = static_cast<std::size_t>(decoded);
  if (n < 2 + kCrcBytes) {
    ++counters_.bad_crc;
    return StatusCode::data_loss;
  }
  const auto body = std::span<const std::byte>(buffer_).first(n - kCrcBytes);
  const std::uint32_t want =
      internal::ByteReader(std::span<const std::byte>(buffer_).subspan(n - kCrcBytes, kCrcBytes))
          .u32();
  if (crc32(body) != want) {
    ++counters_.bad_crc;
    return StatusCode::data_loss;
  }
  ++counters_.frames;
  return body;
}

Result<const LinkMessage*> LinkDecoder::process(std::byte byte) {
  const auto frame = frames_.process(byte);
  if (!frame.ok()) return frame.status();
  const Status s = decode_payload(*frame, message_);
  if (!s.ok()) {
    if (s.code() == StatusCode::not_supported && !frame->empty()) {
      ++other_version_;
      other_version_seen_ = std::to_integer<std::uint8_t>((*frame)[0]);
    }
    ++bad_payload_;
    bad_payload_bytes_ += frame->size();
    return s;
  }
  ++messages_;
  return &message_;
}

DecoderCounters LinkDecoder::counters() const {
  const FrameCounters& f = frames_.counters();
  // A refused payload was a good frame: its bytes count as skipped here.
  return DecoderCounters{messages_,  f.bad_crc,    f.bad_cobs,
                         f.oversize, bad_payload_, f.bytes_skipped + bad_payload_bytes_};
}

}  // namespace twister::link
