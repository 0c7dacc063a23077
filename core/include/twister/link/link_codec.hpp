// Link framing: each message is [version u8][type u8][body][crc32 u32 LE], COBS
// encoded (no zero byte inside) and terminated by one 0x00. A receiver resyncs at
// the next 0x00 after garbage, a torn frame or a restart of the peer; the CRC-32
// (IEEE) rejects corrupted frames. Bodies are little-endian; floats/doubles are
// their IEEE bit patterns. Encoder and decoder write only into caller spans or
// their own fixed arrays: no heap, no I/O.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"
#include "twister/link/link_message.hpp"

namespace twister::link {

// Largest encoded frame: payload + CRC, COBS overhead (1 per 254) and delimiter.
inline constexpr std::size_t kMaxFrameBytes = kMaxPayload + 4 + (kMaxPayload + 4) / 254 + 2;

// Encodes `message` as one frame into `out`; returns the bytes written.
// resource_exhausted: `out` is too small (nothing usable written);
// invalid_argument: a count above its chunk capacity.
// Senders pass the message type itself (encode_frame(hands, out)); the
// LinkMessage overload visits (a decoded message sent on, tests).
template <LinkBody M>
Result<std::size_t> encode_frame(const M& message, std::span<std::byte> out);
Result<std::size_t> encode_frame(const LinkMessage& message, std::span<std::byte> out);

// Parses a payload (version, type, body; CRC already checked) into `out`, which
// then holds the alternative of the frame's type.
// not_supported: other protocol version; invalid_argument: unknown type, wrong
// length or a field out of range (counts, booleans, method).
Status decode_payload(std::span<const std::byte> payload, LinkMessage& out);

struct FrameCounters {
  std::uint64_t frames = 0;         // good frames (CRC and COBS fine)
  std::uint64_t bad_crc = 0;        // CRC mismatch or frame too short
  std::uint64_t bad_cobs = 0;       // COBS structure broken
  std::uint64_t oversize = 0;       // longer than the buffer (dropped to next 0)
  std::uint64_t bytes_skipped = 0;  // bytes of dropped frames
};

// FrameDecoder: the framing layer, byte by byte (pigweed pw_hdlc's Decoder shape).
// Works in a caller-owned buffer (FrameDecoderBuffer<N> owns one); a frame longer
// than the buffer is dropped. No heap, no I/O.
class FrameDecoder {
 public:
  explicit FrameDecoder(std::span<std::byte> buffer) : buffer_(buffer) {}

  // ok: `byte` completed a good frame; the value is its payload (version, type,
  //   body; CRC checked and removed), valid until the next process() or clear().
  // unavailable: no complete frame yet (keep feeding).
  // data_loss: a frame ended with a bad CRC or a broken COBS structure (dropped).
  // resource_exhausted: the frame outgrew the buffer; it is dropped up to the
  //   next delimiter (reported once per frame).
  Result<std::span<const std::byte>> process(std::byte byte);
  // Drops a partial frame (a new peer: its bytes start a fresh frame).
  void clear();
  std::size_t max_size() const { return buffer_.size(); }
  const FrameCounters& counters() const { return counters_; }

 private:
  Result<std::span<const std::byte>> finish_frame();

  std::span<std::byte> buffer_;
  std::size_t size_ = 0;
  bool overflow_ = false;
  FrameCounters counters_{};
};

namespace internal {
template <std::size_t N>
struct FrameStorage {
  std::array<std::byte, N> bytes{};
};
}  // namespace internal

// A FrameDecoder owning a buffer for frames of up to N encoded bytes.
template <std::size_t N = kMaxFrameBytes>
class FrameDecoderBuffer : private internal::FrameStorage<N>, public FrameDecoder {
 public:
  FrameDecoderBuffer() : FrameDecoder(this->bytes) {}
  FrameDecoderBuffer(const FrameDecoderBuffer&) = delete;
  FrameDecoderBuffer& operator=(const FrameDecoderBuffer&) = delete;
};

struct DecoderCounters {
  std::uint64_t frames = 0;         // good messages delivered
  std::uint64_t bad_crc = 0;        // CRC mismatch or frame too short
  std::uint64_t bad_cobs = 0;       // COBS structure broken
  std::uint64_t oversize = 0;       // longer than kMaxFrameBytes (dropped to next 0)
  std::uint64_t bad_payload = 0;    // CRC ok but decode_payload refused it
  std::uint64_t bytes_skipped = 0;  // bytes of dropped frames
};

// LinkDecoder: frames -> messages. Feed bytes as they arrive (any split).
class LinkDecoder {
 public:
  // ok: `byte` completed a good message (valid until the next process()); read it
  // with std::get_if / std::visit or link::type_of.
  // unavailable / data_loss / resource_exhausted: as FrameDecoder::process.
  // invalid_argument / not_supported: a good frame whose payload is not a valid
  //   message of this protocol version (dropped, counted as bad_payload).
  Result<const LinkMessage*> process(std::byte byte);
  // Drops a partial frame and forgets the peer's version: call it for every new
  // connection (a stale partial frame would swallow the new peer's hello).
  void clear();
  DecoderCounters counters() const;
  // Version byte of the last good frame of another protocol version since clear()
  // (0: none): an old or newer peer, refused with a clear message by the caller.
  std::uint8_t other_version() const { return other_version_seen_; }
  std::uint64_t other_version_frames() const { return other_version_; }

 private:
  FrameDecoderBuffer<kMaxFrameBytes> frames_;
  LinkMessage message_{};
  std::uint64_t messages_ = 0;
  std::uint64_t bad_payload_ = 0;
  std::uint64_t bad_payload_bytes_ = 0;
  std::uint64_t other_version_ = 0;
  std::uint8_t other_version_seen_ = 0;
};

// Encoded size of the message (frame bytes incl. delimiter); 0 when it cannot be
// encoded. For link budgets (tests, docs).
template <LinkBody M>
std::size_t frame_size(const M& message);
std::size_t frame_size(const LinkMessage& message);

}  // namespace twister::link
