// Link decoder on arbitrary bytes: never crashes, every delivered frame re-encodes
// to a frame that decodes to the same message (byte-exact), and byte accounting
// holds (skipped bytes never exceed the input).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "twister/link/link_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static twister::link::LinkDecoder decoder;
  decoder = twister::link::LinkDecoder{};
  static std::vector<std::byte> a(twister::link::kMaxFrameBytes);
  static std::vector<std::byte> b(twister::link::kMaxFrameBytes);
  for (std::size_t i = 0; i < size; ++i) {
    if (!decoder.push(static_cast<std::byte>(data[i]))) continue;
    const auto n = twister::link::encode_frame(decoder.message(), a);
    if (!n.ok()) std::abort();
    twister::link::LinkDecoder again;
    bool got = false;
    for (std::size_t k = 0; k < *n; ++k) got = again.push(a[k]) || got;
    if (!got) std::abort();
    const auto m = twister::link::encode_frame(again.message(), b);
    if (!m.ok() || *m != *n) std::abort();
    for (std::size_t k = 0; k < *n; ++k) {
      if (a[k] != b[k]) std::abort();
    }
  }
  if (decoder.counters().bytes_skipped > size) std::abort();
  return 0;
}
