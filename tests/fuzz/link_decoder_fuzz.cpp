// Link decoder on arbitrary bytes: never crashes, every delivered frame re-encodes
// to a frame that decodes to the same message (byte-exact), and byte accounting
// holds (skipped bytes never exceed the input). The same bytes also go straight to
// the payload parser (past the CRC, which random mutations rarely get right), with
// the same re-encoding check for what it accepts.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "twister/link/link_codec.hpp"

namespace {

// The last message a fresh decoder finds in bytes[0, n); null when none.
const twister::link::LinkMessage* decode_all(const std::vector<std::byte>& bytes, std::size_t n) {
  static twister::link::LinkDecoder again;
  again.clear();
  const twister::link::LinkMessage* got = nullptr;
  for (std::size_t k = 0; k < n; ++k) {
    if (const auto m = again.process(bytes[k]); m.ok()) got = *m;
  }
  return got;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static twister::link::LinkDecoder decoder;
  decoder.clear();
  const auto skipped_before = decoder.counters().bytes_skipped;
  static std::vector<std::byte> a(twister::link::kMaxFrameBytes);
  static std::vector<std::byte> b(twister::link::kMaxFrameBytes);
  for (std::size_t i = 0; i < size; ++i) {
    const auto message = decoder.process(static_cast<std::byte>(data[i]));
    if (!message.ok()) continue;
    const auto n = twister::link::encode_frame(**message, a);
    if (!n.ok()) std::abort();
    const twister::link::LinkMessage* got = decode_all(a, *n);
    if (got == nullptr) std::abort();
    const auto m = twister::link::encode_frame(*got, b);
    if (!m.ok() || *m != *n) std::abort();
    for (std::size_t k = 0; k < *n; ++k) {
      if (a[k] != b[k]) std::abort();
    }
  }
  if (decoder.counters().bytes_skipped - skipped_before > size) std::abort();
  static twister::link::LinkMessage direct;
  if (twister::link::decode_payload({reinterpret_cast<const std::byte*>(data), size}, direct)
          .ok()) {
    const auto n = twister::link::encode_frame(direct, a);
    if (!n.ok()) std::abort();
    const twister::link::LinkMessage* got = decode_all(a, *n);
    if (got == nullptr || got->index() != direct.index()) std::abort();
  }
  return 0;
}
