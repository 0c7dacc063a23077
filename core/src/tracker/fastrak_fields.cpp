// Fixed-width field codecs. Values go through an integer mantissa and a power of ten
// in double so that parse(write(x)) is exact for values already on the field's grid.
#include "fastrak_fields.hpp"

#include <cmath>

namespace twister::tracker::internal {
namespace {

double pow10i(int e) {
  double r = 1.0;
  for (int i = 0; i < e; ++i) r *= 10.0;
  return r;
}

// Scales an integer mantissa by 10^e with a single rounding.
double scale(std::int64_t mantissa, int e) {
  // Dividing by an exact power of ten rounds once; multiplying by 0.1^n would not.
  if (e >= 0) return static_cast<double>(mantissa) * pow10i(e);
  return static_cast<double>(mantissa) / pow10i(-e);
}

}  // namespace

bool parse_fixed(const std::byte* p, std::size_t width, int decimals, float& out) {
  std::size_t i = 0;
  while (i < width && ch(p[i]) == ' ') ++i;
  bool negative = false;
  if (i < width && (ch(p[i]) == '-' || ch(p[i]) == '+')) {
    negative = ch(p[i]) == '-';
    ++i;
    while (i < width && ch(p[i]) == ' ') ++i;  // sign-column style
  }
  const std::size_t int_start = i;
  std::int64_t mantissa = 0;
  while (i < width && is_digit(ch(p[i]))) {
    mantissa = mantissa * 10 + (ch(p[i]) - '0');
    ++i;
  }
  if (i == int_start) return false;
  const auto dec = static_cast<std::size_t>(decimals);
  if (i + 1 + dec != width || ch(p[i]) != '.') return false;
  ++i;
  for (; i < width; ++i) {
    if (!is_digit(ch(p[i]))) return false;
    mantissa = mantissa * 10 + (ch(p[i]) - '0');
  }
  const double v = scale(negative ? -mantissa : mantissa, -decimals);
  out = static_cast<float>(v);
  return true;
}

void write_fixed(std::byte* p, std::size_t width, int decimals, float value) {
  double scaled = static_cast<double>(value);
  for (int i = 0; i < decimals; ++i) scaled *= 10.0;
  std::int64_t m = std::isfinite(scaled) ? std::llround(scaled) : 0;
  // Largest magnitude the field holds: width minus '.' (minus sign when negative).
  const std::size_t digits = width - 1;
  std::int64_t limit = 1;
  for (std::size_t i = 0; i < digits; ++i) limit *= 10;
  const std::int64_t pos_max = limit - 1;
  const std::int64_t neg_max = limit / 10 - 1;
  if (m > pos_max) m = pos_max;
  if (m < -neg_max) m = -neg_max;
  const bool negative = m < 0;
  std::uint64_t a = static_cast<std::uint64_t>(negative ? -m : m);
  std::size_t pos = width;
  const auto dec = static_cast<std::size_t>(decimals);
  for (std::size_t k = 0; k < dec; ++k) {
    p[--pos] = static_cast<std::byte>('0' + static_cast<int>(a % 10));
    a /= 10;
  }
  p[--pos] = static_cast<std::byte>('.');
  do {
    p[--pos] = static_cast<std::byte>('0' + static_cast<int>(a % 10));
    a /= 10;
  } while (a != 0 && pos > 0);
  if (negative && pos > 0) p[--pos] = static_cast<std::byte>('-');
  while (pos > 0) p[--pos] = static_cast<std::byte>(' ');
}

double packed16_scale(Item item, Units units) {
  switch (item) {
    case Item::position:
      return (units == Units::inches ? kPacked16PositionFullScaleIn
                                     : kPacked16PositionFullScaleCm) /
             32768.0;
    case Item::euler:
      return kPacked16AngleFullScaleDeg / 32768.0;
    default:
      return 1.0 / kPacked16UnitCounts;  // direction cosines, quaternion parts
  }
}

float read_packed16(const std::byte* p, double scale) {
  const auto raw =
      static_cast<std::uint16_t>(static_cast<unsigned>(p[0]) | (static_cast<unsigned>(p[1]) << 8));
  const auto counts = static_cast<std::int16_t>(raw);
  return static_cast<float>(static_cast<double>(counts) * scale);
}

void write_packed16(std::byte* p, double scale, float value) {
  const double c = static_cast<double>(value) / scale;
  const long counts =
      std::isfinite(c) ? std::lround(std::fmax(-32768.0, std::fmin(32767.0, c))) : 0;
  const auto raw = static_cast<std::uint16_t>(static_cast<std::int16_t>(counts));
  p[0] = static_cast<std::byte>(raw & 0xFFu);
  p[1] = static_cast<std::byte>(raw >> 8);
}

bool parse_extended(const std::byte* p, float& out) {
  const char sign = ch(p[0]);
  if (sign != ' ' && sign != '-' && sign != '+') return false;
  if (!is_digit(ch(p[1])) || ch(p[2]) != '.') return false;
  std::int64_t m = ch(p[1]) - '0';
  for (int i = 3; i < 8; ++i) {
    if (!is_digit(ch(p[i]))) return false;
    m = m * 10 + (ch(p[i]) - '0');
  }
  if ((ch(p[8]) != 'E' && ch(p[8]) != 'e') || (ch(p[9]) != '+' && ch(p[9]) != '-')) return false;
  if (!is_digit(ch(p[10])) || !is_digit(ch(p[11])) || ch(p[12]) != ' ') return false;
  int e = (ch(p[10]) - '0') * 10 + (ch(p[11]) - '0');
  if (ch(p[9]) == '-') e = -e;
  const double v = scale(sign == '-' ? -m : m, e - 5);
  const float f = static_cast<float>(v);
  if (!std::isfinite(f)) return false;
  out = f;
  return true;
}

void write_extended(std::byte* p, float value) {
  double a = std::fabs(static_cast<double>(value));
  if (!std::isfinite(a)) a = 0.0;
  int e = 0;
  std::int64_t m = 0;
  if (a > 0.0) {
    e = static_cast<int>(std::floor(std::log10(a)));
    m = std::llround(scale(1, 5 - e) * a);
    if (m >= 1000000) {  // rounding carried into an extra digit
      ++e;
      m = std::llround(scale(1, 5 - e) * a);
    }
    if (e > 99 || e < -99) {
      e = 0;
      m = 0;
    }
  }
  p[0] = static_cast<std::byte>(value < 0.0f && m != 0 ? '-' : ' ');
  std::int64_t rest = m;
  for (int i = 7; i >= 3; --i) {
    p[i] = static_cast<std::byte>('0' + static_cast<int>(rest % 10));
    rest /= 10;
  }
  p[2] = static_cast<std::byte>('.');
  p[1] = static_cast<std::byte>('0' + static_cast<int>(rest % 10));
  p[8] = static_cast<std::byte>('E');
  p[9] = static_cast<std::byte>(e < 0 ? '-' : '+');
  const int ae = e < 0 ? -e : e;
  p[10] = static_cast<std::byte>('0' + ae / 10);
  p[11] = static_cast<std::byte>('0' + ae % 10);
  p[12] = static_cast<std::byte>(' ');
}

}  // namespace twister::tracker::internal
