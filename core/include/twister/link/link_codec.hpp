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
Result<std::size_t> encode_frame(const LinkMessage& message, std::span<std::byte> out);

// Parses a payload (version, type, body; CRC already checked) into `out`.
// not_supported: other protocol version; invalid_argument: unknown type, wrong
// length or a field out of range (counts, booleans, method).
Status decode_payload(std::span<const std::byte> payload, LinkMessage& out);

struct DecoderCounters {
  std::uint64_t frames = 0;         // good frames delivered
  std::uint64_t bad_crc = 0;        // CRC mismatch or frame too short
  std::uint64_t bad_cobs = 0;       // COBS structure broken
  std::uint64_t oversize = 0;       // longer than kMaxFrameBytes (dropped to next 0)
  std::uint64_t bad_payload = 0;    // CRC ok but decode_payload refused it
  std::uint64_t bytes_skipped = 0;  // bytes of dropped frames
};

// Byte-wise frame decoder: feed bytes as they arrive (any split); message() holds
// the last good frame after push() returned true.
class LinkDecoder {
 public:
  // true when `byte` completed a good frame (see message()); bad frames are
  // counted and skipped.
  bool push(std::byte byte);
  const LinkMessage& message() const { return message_; }
  const DecoderCounters& counters() const { return counters_; }
  // Drops a partial frame (the peer reconnected).
  void reset();

 private:
  bool finish_frame();

  std::array<std::byte, kMaxFrameBytes> buffer_{};
  std::size_t size_ = 0;
  bool overflow_ = false;
  LinkMessage message_{};
  DecoderCounters counters_{};
};

}  // namespace twister::link
