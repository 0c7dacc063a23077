// Little-endian cursor over a fixed byte span, shared by the journal record and link
// payload codecs (public only so both core libraries can include it). Writes past the
// end and reads past the end set a sticky failure flag instead of touching memory, so
// callers check once at the end.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>

namespace twister::internal {

class ByteWriter {
 public:
  explicit ByteWriter(std::span<std::byte> out) : out_(out) {}
  void u8(std::uint8_t v) { put(v, 1); }
  void u16(std::uint16_t v) { put(v, 2); }
  void u32(std::uint32_t v) { put(v, 4); }
  void u64(std::uint64_t v) { put(v, 8); }
  void f32(float v) { put(std::bit_cast<std::uint32_t>(v), 4); }
  void f64(double v) { put(std::bit_cast<std::uint64_t>(v), 8); }
  void vec(const glm::dvec3& v) {
    f64(v.x);
    f64(v.y);
    f64(v.z);
  }
  bool ok() const { return ok_; }
  std::size_t size() const { return size_; }

 private:
  void put(std::uint64_t v, std::size_t n) {
    if (!ok_ || out_.size() - size_ < n) {
      ok_ = false;
      return;
    }
    for (std::size_t i = 0; i < n; ++i)
      out_[size_++] = static_cast<std::byte>((v >> (8 * i)) & 0xffu);
  }
  std::span<std::byte> out_;
  std::size_t size_ = 0;
  bool ok_ = true;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::byte> in) : in_(in) {}
  std::uint8_t u8() { return static_cast<std::uint8_t>(get(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(get(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(get(4)); }
  std::uint64_t u64() { return get(8); }
  float f32() { return std::bit_cast<float>(static_cast<std::uint32_t>(get(4))); }
  double f64() { return std::bit_cast<double>(get(8)); }
  glm::dvec3 vec() {
    const double x = f64();
    const double y = f64();
    const double z = f64();
    return {x, y, z};
  }
  bool ok() const { return ok_; }
  bool at_end() const { return pos_ == in_.size(); }

 private:
  std::uint64_t get(std::size_t n) {
    if (!ok_ || in_.size() - pos_ < n) {
      ok_ = false;
      return 0;
    }
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) {
      v |= static_cast<std::uint64_t>(std::to_integer<std::uint8_t>(in_[pos_++])) << (8 * i);
    }
    return v;
  }
  std::span<const std::byte> in_;
  std::size_t pos_ = 0;
  bool ok_ = true;
};

}  // namespace twister::internal
