// In-record corruption of encoded records (see record_corruption.hpp).
#include "record_corruption.hpp"

#include <array>

namespace twister::sim {
namespace {

using tracker::Format;
using tracker::Item;

bool is_number_item(Item item) {
  return item != Item::space && item != Item::crlf && item != Item::stylus &&
         item != Item::stylus_ext;
}

unsigned pick(std::mt19937& rng, unsigned n) { return static_cast<unsigned>(rng() % n); }

bool is_digit(std::byte b) { return b >= std::byte{'0'} && b <= std::byte{'9'}; }

// One ASCII field of `width` characters at p: a digit flipped to another digit, or
// the sign moved / removed.
void corrupt_ascii_field(std::byte* p, std::size_t width, std::mt19937& rng) {
  std::size_t first = 0;  // first non-blank character
  while (first < width && p[first] == std::byte{' '}) ++first;
  const bool extended = width == 13;
  if (pick(rng, 4) == 0) {  // the sign
    if (extended) {
      p[0] = p[0] == std::byte{'-'} ? std::byte{' '} : std::byte{'-'};
    } else if (first < width && p[first] == std::byte{'-'}) {
      p[first] = std::byte{' '};
    } else if (first > 0) {
      p[first - 1] = std::byte{'-'};
    }
    return;
  }
  std::array<std::size_t, 13> digits{};
  std::size_t n = 0;
  const std::size_t end = extended ? 8 : width;  // not the exponent of `Sx.xxxxxESxx `
  for (std::size_t i = 0; i < end; ++i) {
    if (is_digit(p[i])) digits[n++] = i;
  }
  if (n == 0) return;
  std::byte& d = p[digits[pick(rng, static_cast<unsigned>(n))]];
  for (;;) {  // bit 0 always gives another digit; bits 1-3 only sometimes
    const std::byte flipped = d ^ static_cast<std::byte>(1u << pick(rng, 4));
    if (is_digit(flipped)) {
      d = flipped;
      return;
    }
  }
}

}  // namespace

bool corrupt_record(std::span<std::byte> record, int station, const tracker::FastrakConfig& config,
                    std::mt19937& rng) {
  const tracker::OutputList& list = config.stations[static_cast<std::size_t>(station - 1)].list;
  const Format fmt = config.format;
  // Number items and their offsets (logical bytes for binary16).
  std::array<std::size_t, tracker::kMaxItems> offset{};
  std::array<Item, tracker::kMaxItems> item{};
  std::size_t n = 0;
  std::size_t off = tracker::kHeaderBytes;
  for (std::size_t i = 0; i < list.count; ++i) {
    if (is_number_item(list.items[i])) {
      offset[n] = off;
      item[n++] = list.items[i];
    }
    off += tracker::item_width(list.items[i], fmt, config.ascii_stylus_width);
  }
  if (n == 0) return false;
  const std::size_t k = pick(rng, static_cast<unsigned>(n));
  const std::size_t width = tracker::item_width(item[k], fmt, config.ascii_stylus_width);
  if (fmt == Format::ascii) {
    const std::size_t field = item[k] >= Item::position_ext ? 13 : 7;
    corrupt_ascii_field(
        record.data() + offset[k] + field * pick(rng, static_cast<unsigned>(width / field)), field,
        rng);
    return true;
  }
  if (fmt == Format::binary) {
    record[offset[k] + pick(rng, static_cast<unsigned>(width))] ^=
        static_cast<std::byte>(1u << pick(rng, 8));
    return true;
  }
  std::array<std::byte, tracker::kMaxRecordBytes> logical{};
  if (!tracker::unpack16(record.data(), record.size(), logical.data())) return false;
  logical[offset[k] + pick(rng, static_cast<unsigned>(width))] ^=
      static_cast<std::byte>(1u << pick(rng, 8));
  tracker::pack16(logical.data(), tracker::unpacked16_length(record.size()), record.data());
  return true;
}

}  // namespace twister::sim
